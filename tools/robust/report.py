# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""The randomized campaign's report: success rate, failures with the command that
reproduces each, the distributions of angle and speed error, and plots.

Usage: report.py <runs.csv> <out dir> [expected runs]
       (also: an1078-robust-report, python -m robust.report)
Reads the rows tools/sim/robust wrote (tools/robust/run merges them), prints
the summary and writes <out dir>/robust.png (when matplotlib is there).
Exit status 1 if a run failed inside the envelope or rows are missing.
"""

from __future__ import annotations

import csv
import math
import os
import sys
from collections import OrderedDict

Row = dict[str, str]

DIST = [
    ("ang_mean", "angle error, mean (deg)", False),
    ("ang_rms", "angle error, rms (deg)", False),
    ("ang_max", "angle error, max |.| (deg)", False),
    ("spd_err_pct", "speed error, true vs reference (%)", True),
    ("est_err_pct", "speed estimate vs true (%)", True),
    ("spd_err2_pct", "speed error after the step (%)", True),
    ("spd_rip_pct", "speed ripple, rms (%)", False),
    ("spd_rip2_pct", "speed ripple after the step (%)", False),
    ("t_cl_s", "START to CLOSED_LOOP (s)", False),
    ("i_peak", "peak phase current (A)", False),
]


def pct(values: list[float], p: float) -> float:
    """The p-th percentile (nearest rank) of a non-empty list."""
    s = sorted(values)
    k = max(0, min(len(s) - 1, math.ceil(p / 100.0 * len(s)) - 1))
    return s[k]


def fnum(r: Row, key: str) -> float:
    return float(r[key])


def main(argv: list[str] | None = None) -> int:
    """argv as sys.argv (the program's name first)."""
    argv = sys.argv if argv is None else argv
    if len(argv) < 3:
        print("usage: report.py <runs.csv> <out dir> [expected runs]", file=sys.stderr)
        return 2
    path, out = argv[1], argv[2]
    expected = int(argv[3]) if len(argv) > 3 else 0
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print(f"robust: cannot read {path}: {e.strerror}", file=sys.stderr)
        return 2
    by: OrderedDict[str, list[Row]] = OrderedDict()
    for r in rows:
        by.setdefault(r["motor"], []).append(r)

    status = 0
    total = {"PASS": 0, "SAFE": 0, "FAIL": 0}
    print(f"== robust: {len(rows)} runs")
    print(f"   {'profile':10s} {'runs':>5s} {'pass':>5s} {'safe':>5s} {'fail':>5s}  "
          f"{'success':>8s}  {'outside the claim':>18s}")
    for motor, rs in by.items():
        n = {k: sum(1 for r in rs if r["result"] == k) for k in total}
        for k in total:
            total[k] += n[k]
        outside = sum(1 for r in rs if r["physics_limited"] == "1" or r["step_limited"] == "1")
        ok = 100.0 * (n["PASS"] + n["SAFE"]) / len(rs)
        print(f"   {motor:10s} {len(rs):5d} {n['PASS']:5d} {n['SAFE']:5d} {n['FAIL']:5d}  "
              f"{ok:7.2f}%  {outside:18d}")
    ok_all = 100.0 * (total["PASS"] + total["SAFE"]) / max(1, len(rows))
    print(f"   {'all':10s} {len(rows):5d} {total['PASS']:5d} {total['SAFE']:5d} {total['FAIL']:5d}  "
          f"{ok_all:7.2f}%")
    print("   success = PASS (started, reached speed, held, took the step, stopped) + SAFE (outside")
    print("   the envelope the profile claims, ended in the right fault with the outputs off)")
    if expected and len(rows) != expected:
        print(f"robust: {len(rows)} rows for {expected} runs: a run crashed", file=sys.stderr)
        status = 1

    fails = [r for r in rows if r["result"] == "FAIL"]
    if fails:
        status = 1
        print(f"\n== failures ({len(fails)}), each with the command that reproduces it")
        for r in fails:
            print(f"   seed {r['seed']:>6s} {r['motor']:9s} {r['why']}: J x{fnum(r, 'j_scale'):.2f}, "
                  f"{r['load']} {fnum(r, 'load_nm') * 1000:.1f} mN m, step {r['step']}, "
                  f"{r['inverter']} {fnum(r, 'deadtime_us'):.2f} us")
            print(f"      {r['binary']} --motor {r['motor']} --board {r['board']} --seed {r['seed']} "
                  f"--csv seed{r['seed']}.csv")
    safe = [r for r in rows if r["result"] == "SAFE"]
    if safe:
        faults: dict[str, int] = {}
        for r in safe:
            faults[r["fault"]] = faults.get(r["fault"], 0) + 1
        print(f"\n== outside the claim, failed safe ({len(safe)}): "
              + ", ".join(f"{k} {v}" for k, v in sorted(faults.items())))

    print("\n== distributions over the passing runs (hold window unless said)")
    print(f"   {'':38s} {'profile':9s} {'p50':>8s} {'p90':>8s} {'p99':>8s} {'max':>8s}")
    for key, label, absval in DIST:
        for motor, rs in by.items():
            v = [fnum(r, key) for r in rs if r["result"] == "PASS"]
            if not v:
                continue
            if absval:
                v = [abs(x) for x in v]
            lab = ("|" + label + "|") if absval else label
            print(f"   {lab:38s} {motor:9s} {pct(v, 50):8.3f} {pct(v, 90):8.3f} {pct(v, 99):8.3f} "
                  f"{max(v):8.3f}")

    plot(rows, by, out)
    return status


def plot(rows: list[Row], by: OrderedDict[str, list[Row]], out: str) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("robust: no matplotlib (run tools/bootstrap): plots skipped", file=sys.stderr)
        return
    fig, ax = plt.subplots(2, 3, figsize=(16, 9))
    for motor, rs in by.items():
        ok = [r for r in rs if r["result"] == "PASS"]
        ax[0][0].hist([fnum(r, "ang_rms") for r in ok], bins=40, alpha=0.5, label=motor)
        ax[0][1].hist([abs(fnum(r, "spd_err_pct")) for r in ok], bins=40, alpha=0.5, label=motor)
        ax[0][2].scatter([fnum(r, "l_scale") for r in ok], [fnum(r, "ang_mean") for r in ok], s=5,
                         label=motor)
        ax[1][0].scatter([fnum(r, "deadtime_us") for r in ok], [fnum(r, "ang_mean") for r in ok], s=5,
                         label=motor)
        ax[1][2].hist([fnum(r, "t_cl_s") for r in ok], bins=40, alpha=0.5, label=motor)
    colours = {"PASS": "tab:green", "SAFE": "tab:orange", "FAIL": "tab:red"}
    for res, c in colours.items():
        sel = [r for r in rows if r["result"] == res]
        ax[1][1].scatter([fnum(r, "j_scale") for r in sel],
                         [fnum(r, "start_need_nm") / fnum(r, "start_have_nm") for r in sel], s=8, c=c,
                         label=f"{res} ({len(sel)})")
    ax[1][1].axhline(1.0, color="k", lw=0.8)
    ax[1][1].set_xscale("log")
    titles = [["angle error rms, hold (deg)", "|speed error|, hold (%)", "mean angle error vs L scale"],
              ["mean angle error vs dead time (us)", "start need / claim vs inertia scale (all runs)",
               "START to CLOSED_LOOP (s)"]]
    for i in range(2):
        for j in range(3):
            ax[i][j].set_title(titles[i][j])
            ax[i][j].legend(fontsize=8)
            ax[i][j].grid(alpha=0.3)
    fig.suptitle(f"robust: {len(rows)} randomized runs (docs/robustness.md)")
    fig.tight_layout()
    png = os.path.join(out, "robust.png")
    fig.savefig(png, dpi=90)
    print(f"\n   plots: {png}")


if __name__ == "__main__":
    sys.exit(main())
