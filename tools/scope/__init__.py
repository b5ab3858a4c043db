# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""The PC side of the X2Cscope target (firmware/x2cscope, docs/x2cscope.md): LNet frames and
transports (lnet), the services and the scope (x2c), the variable map (varmap, an1078-x2cmap),
the command an1078-scope (cli), and the core's state and fault names (mc_names)."""
