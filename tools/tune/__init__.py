# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""tools/tune: the motor profile calculator (motortune) and its examples (docs/tune.md)."""
