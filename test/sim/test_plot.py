#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""tools/sim/plot.py: one line and a non-zero exit for a bad input, never a traceback; nothing
written but the .png asked for; a trace cut short by a diverged plant still plots."""
from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest

if importlib.util.find_spec("matplotlib") is None:  # CTest: SKIP_RETURN_CODE 77
    print("SKIPPED: matplotlib is not installed (tools/requirements.txt: run tools/bootstrap)")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
PLOT = os.path.join(HERE, "..", "..", "tools", "sim", "plot.py")
HEADER = ("t_s,state,fault,speed_target_rpm,speed_ref_rpm,speed_est_rpm,speed_rpm,theta_est_deg,theta_deg,"
          "theta_err_deg,id_ref_A,id_A,iq_ref_A,iq_A,id_true_A,iq_true_A,ia_A,ib_A,ic_A,duty_a,duty_b,duty_c,"
          "outputs_on,vbus_V,load_Nm,torque_Nm,vd_V,vq_V,estimator_valid,zoom")


def row(t: float, speed: str = "1000") -> str:
    return ",".join([f"{t:.6f}", "4", "0", "1000", "1000", "1000", speed] + ["0"] * 15 + ["1", "24", "0", "0",
                                                                                         "0", "0", "1", "0"])


class PlotFailsInOneLine(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory(prefix="test_plot_")
        self.dir = self.tmp.name

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def trace(self, rows: list[str]) -> str:
        p = os.path.join(self.dir, "t.csv")
        with open(p, "w") as f:
            f.write(HEADER + "\n" + "\n".join(rows) + "\n")
        return p

    def plot(self, *args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, PLOT, *args], capture_output=True, text=True, timeout=120)

    def assertOneLine(self, r: subprocess.CompletedProcess[str], want: str) -> None:
        self.assertNotEqual(r.returncode, 0)
        self.assertNotIn("Traceback", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn(want, r.stderr)

    def test_an_output_not_named_png_should_be_refused_and_nothing_written(self) -> None:
        t = self.trace([row(k * 1e-3) for k in range(50)])
        self.assertOneLine(self.plot(t, os.path.join(self.dir, "out")), "must end in .png")
        self.assertEqual(sorted(os.listdir(self.dir)), ["t.csv"])

    def test_a_missing_or_foreign_trace_should_be_one_line(self) -> None:
        self.assertOneLine(self.plot(os.path.join(self.dir, "none.csv"), os.path.join(self.dir, "a.png")),
                           "cannot read the trace")
        p = os.path.join(self.dir, "x.csv")
        with open(p, "w") as f:
            f.write("a,b\n1,2\n")
        self.assertOneLine(self.plot(p, os.path.join(self.dir, "a.png")), "not a simulator trace")

    def test_a_trace_ending_in_a_non_finite_row_should_plot_what_came_before(self) -> None:
        t = self.trace([row(k * 1e-3) for k in range(50)] + [row(0.05, "nan")])
        out = os.path.join(self.dir, "a.png")
        r = self.plot(t, out)
        self.assertEqual((r.returncode, r.stderr), (0, ""))
        with open(out, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertEqual(sorted(os.listdir(self.dir)), ["a.png", "t.csv"])


if __name__ == "__main__":
    unittest.main(verbosity=2)
