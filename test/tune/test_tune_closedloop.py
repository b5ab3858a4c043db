# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Closed-loop proof of tools/tune (label slow): each example description's generated
profile (firmware/motors/motor_<name>.h, checked up to date by test_tune_unit) drives
the simulated motor with no hand edits: it starts, reaches closed loop, and holds the
requested speed.

The simulator programs sim_tune_<name> are built by test/tune/CMakeLists.txt (the core
compiled with MC_MOTOR_HEADER="motors/motor_<name>.h"); TUNE_SIM_DIR says where.
"""

from __future__ import annotations

import csv
import os
import re
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
SCEN = os.path.join(REPO, "tools", "sim", "scenarios")
SIM_DIR = os.environ.get("TUNE_SIM_DIR", "")

# profile -> (simulated plant, board, [(scenario, speed to hold in rpm, hold window s)])
CASES: dict[str, tuple[str, str, list[tuple[str, float, float]]]] = {
    "hurst075": ("hurst", "mclv", [("run_1000", 1000.0, 0.5), ("run_2000", 2000.0, 0.5)]),
    "hurst_long": ("hurst300", "mclv", [("run_1000", 1000.0, 0.5), ("run_2000", 2000.0, 0.5)]),
    "hs2p": ("hispeed", "mchv", [("high_speed", 17000.0, 0.4)]),
}
TOL = 0.02  # speed held within 2 % of the request, mean over the hold window


def run_sim(profile: str, plant: str, board: str, scenario: str) -> tuple[subprocess.CompletedProcess[str],
                                                                           list[dict[str, str]]]:
    exe = os.path.join(SIM_DIR, f"sim_tune_{profile}")
    with tempfile.TemporaryDirectory(prefix="tune_cl_") as d:
        trace = os.path.join(d, "trace.csv")
        p = subprocess.run([exe, "--motor", plant, "--board", board, "--no-progress", "--csv", trace,
                            os.path.join(SCEN, scenario + ".txt")], capture_output=True, text=True, timeout=500)
        with open(trace) as f:
            rows = list(csv.DictReader(f))
    return p, rows


class GeneratedProfilesInClosedLoop(unittest.TestCase):
    def setUp(self) -> None:
        if not SIM_DIR or not os.path.isdir(SIM_DIR):
            self.skipTest("TUNE_SIM_DIR not set: run through CTest (the sim_tune_* programs are built there)")

    def check(self, profile: str) -> None:
        plant, board, runs = CASES[profile]
        exe = os.path.join(SIM_DIR, f"sim_tune_{profile}")
        if not os.path.exists(exe):
            self.skipTest(f"{exe} not built (the simulator target is missing)")
        for scenario, rpm, window in runs:
            with self.subTest(scenario):
                p, rows = run_sim(profile, plant, board, scenario)
                self.assertEqual(p.returncode, 0, p.stderr)
                m = re.search(r"faults\s+(\d+)", p.stdout)
                self.assertTrue(m and m.group(1) == "0", p.stdout)
                sm = re.search(r"states\s+(.*)", p.stdout)
                tm = re.search(r"time to closed loop\s+([\d.]+) s", p.stdout)
                assert sm is not None and tm is not None, p.stdout
                states = sm.group(1).split()
                self.assertTrue(states[-1].endswith(":CLOSED_LOOP"), f"ends in {states[-1]}\n{p.stdout}")
                t_cl = float(tm.group(1))
                t_end = float(rows[-1]["t_s"])
                hold = [r for r in rows if float(r["t_s"]) >= t_end - window]
                speed = sum(float(r["speed_rpm"]) for r in hold) / len(hold)
                est = sum(float(r["speed_est_rpm"]) for r in hold) / len(hold)
                worst = max(abs(float(r["speed_rpm"]) - rpm) for r in hold)
                ang = max(abs(float(r["theta_err_deg"])) for r in hold)
                print(f"measured: {profile} on {plant}/{board}, {scenario}: closed loop {t_cl:.3f} s after "
                      f"the start request, speed over the last {window} s mean {speed:.1f} rpm "
                      f"({100 * (speed - rpm) / rpm:+.2f} % of {rpm:.0f}), worst sample {worst:.1f} rpm off, "
                      f"estimate {est:.1f} rpm, max angle error {ang:.1f} deg, states {' '.join(states)}")
                self.assertLessEqual(abs(speed - rpm), TOL * rpm)
                self.assertLessEqual(worst, 2 * TOL * rpm)

    def test_generated_hurst075_profile_should_start_and_hold_1000_and_2000_rpm(self) -> None:
        self.check("hurst075")

    def test_generated_hurst300_profile_should_start_and_hold_1000_and_2000_rpm(self) -> None:
        self.check("hurst_long")

    def test_generated_hispeed_profile_should_start_and_hold_17000_rpm_on_the_mchv(self) -> None:
        self.check("hs2p")


if __name__ == "__main__":
    unittest.main()
