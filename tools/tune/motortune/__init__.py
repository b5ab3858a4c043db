# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""motortune: a motor's data sheet (TOML) to a motor profile header, and a profile back in
engineering units, with the core's own arithmetic and checks read through a C probe."""
