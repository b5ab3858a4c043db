# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""python -m tune.motortune: the tools/tune/tune command."""

import sys

if sys.version_info < (3, 11):  # noqa: UP036 - the one line an older python3 must print
    sys.exit("tune: needs Python 3.11 or newer (tomllib)")

from tune.motortune.cli import main

sys.exit(main())
