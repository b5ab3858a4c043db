# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""python tools/scope (or python -m scope, or an1078-scope): the X2Cscope client's command."""

import sys

from scope.cli import main

sys.exit(main())
