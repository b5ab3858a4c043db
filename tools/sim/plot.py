#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""plot.py - the plots of one simulator run: build/sim/<scenario>.csv -> <scenario>.png.

Usage: plot.py <trace.csv> <out.png> [title]   (also: an1078-plot, python -m sim.plot)

Left column, the whole run: speed (reference, estimated, true), d-q currents
with their references, estimated-minus-true electrical angle, phase currents,
duties, state with load torque and bus voltage. Right column, a close-up of
the first `zoom` window of the scenario (every PWM period): estimated versus
true electrical angle, phase currents, duties.
"""
from __future__ import annotations

import contextlib
import os
import sys
from typing import Any, NoReturn

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from scope import mc_names

Trace = Any  # a numpy structured array, one field per CSV column


def fail(msg: str) -> NoReturn:
    """One line on stderr, exit status 1: never a traceback."""
    sys.exit("plot.py: " + msg.replace("\n", " "))


def load(path: str) -> Trace:
    try:
        d = np.genfromtxt(path, delimiter=",", names=True)
    except (OSError, ValueError) as e:
        fail("%r: cannot read the trace (%s)" % (path, e))
    if d.size == 0 or d.dtype.names is None or "t_s" not in d.dtype.names:
        fail("%r: not a simulator trace" % path)
    d = np.atleast_1d(d)
    # a run stopped on a diverged plant may end in a non-finite row: the plot
    # covers what came before it
    finite = np.isfinite(d["speed_rpm"]) & np.isfinite(d["iq_A"]) & np.isfinite(d["t_s"])
    if not np.all(finite):
        d = d[: int(np.argmin(finite))]
        if d.size == 0:
            fail("%r: no finite row" % path)
    return d


def save(fig: Figure, out: str) -> None:
    """Written beside out under a temporary name and renamed over it: a
    failure leaves an earlier plot as it was."""
    tmp = os.path.join(os.path.dirname(out) or ".", ".%s.tmp.png" % os.path.basename(out))
    try:
        fig.savefig(tmp, bbox_inches="tight", format="png")
        os.replace(tmp, out)
    except OSError as e:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        fail("%r: cannot write the plot (%s)" % (out, e))


def zoom_window(d: Trace) -> tuple[Any, bool]:
    """Rows of the first zoom window, or the last 20 ms of the run."""
    z = d["zoom"] > 0.5
    if np.any(z):
        idx = np.flatnonzero(z)
        gaps = np.flatnonzero(np.diff(idx) > 1)
        end = idx[gaps[0]] if gaps.size else idx[-1]
        return np.arange(idx[0], end + 1), True
    t = d["t_s"]
    return np.flatnonzero(t >= t[-1] - 0.02), False


# Background per state, by the core's names (firmware/mc.h MC_STATE_LIST).
STATE_COLOURS = {"LOCK": "#fff2cc", "OPEN_LOOP": "#fde0c5", "CLOSED_LOOP": "#e2f0d9", "IDENTIFY": "#e4dcf2",
                 "FAULT": "#f8cbcb"}


def shade_states(ax: Axes, t: Any, state: Any) -> None:
    """Light background per start-up / closed-loop / identification / fault interval."""
    names = mc_names.read()
    colours = {names.states.index(n): c for n, c in STATE_COLOURS.items() if n in names.states}
    if t.size < 2:
        return
    change = np.flatnonzero(np.diff(state) != 0) + 1
    starts = np.concatenate(([0], change))
    ends = np.concatenate((change, [t.size - 1]))
    for a, b in zip(starts, ends, strict=False):
        c = colours.get(int(state[a]))
        if c:
            ax.axvspan(t[a], t[b], color=c, lw=0, zorder=0)


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) < 2:
        fail("usage: plot.py <trace.csv> <out.png> [title]")
    if not args[1].lower().endswith(".png"):
        # matplotlib would pick the format from the name: a file not asked for
        fail("%r: the output name must end in .png" % args[1])
    names = mc_names.read()
    d = load(args[0])
    title = args[2] if len(args) > 2 else args[0]
    t = d["t_s"]
    st = d["state"].astype(int)

    fig = plt.figure(figsize=(17, 15), dpi=100)
    gs = fig.add_gridspec(6, 2, width_ratios=[2.4, 1], hspace=0.38, wspace=0.32)
    axs = [fig.add_subplot(gs[0, 0])]
    for r in range(1, 6):
        axs.append(fig.add_subplot(gs[r, 0], sharex=axs[0]))
    fig.suptitle(title, fontsize=13, y=0.915)

    ax = axs[0]
    shade_states(ax, t, st)
    ax.plot(t, d["speed_target_rpm"], color="0.6", ls=":", lw=1.2, label="target (pot)")
    ax.plot(t, d["speed_ref_rpm"], color="k", ls="--", lw=1.2, label="reference (ramped)")
    ax.plot(t, d["speed_est_rpm"], color="tab:orange", lw=1.0, label="estimated")
    ax.plot(t, d["speed_rpm"], color="tab:blue", lw=1.2, label="true (plant)")
    # Scale to the true speed and the references; an estimate that runs
    # away while it is not used (stopped, lock) is clipped, not allowed to
    # squash the rest.
    hi = max(np.max(d["speed_rpm"]), np.max(d["speed_ref_rpm"]), np.max(d["speed_target_rpm"]))
    lo = min(0.0, np.min(d["speed_rpm"]))
    pad = 0.08 * max(hi - lo, 100.0)
    ax.set_ylim(lo - pad, hi + pad)
    ax.set_ylabel("speed [rpm]")
    ax.set_title("mechanical speed (background: yellow LOCK, orange OPEN_LOOP, "
                 "green CLOSED_LOOP, purple IDENTIFY, red FAULT)", fontsize=9)
    ax.legend(loc="upper left", fontsize=8, ncol=4)
    ax.grid(alpha=0.3)

    ax = axs[1]
    shade_states(ax, t, st)
    ax.plot(t, d["iq_ref_A"], color="tab:red", ls="--", lw=1.0, label="iq ref")
    ax.plot(t, d["iq_A"], color="tab:red", lw=0.8, label="iq (core)")
    ax.plot(t, d["iq_true_A"], color="darkred", lw=0.6, alpha=0.6, label="iq (true frame)")
    ax.plot(t, d["id_ref_A"], color="tab:green", ls="--", lw=1.0, label="id ref")
    ax.plot(t, d["id_A"], color="tab:green", lw=0.8, label="id (core)")
    ax.plot(t, d["id_true_A"], color="darkgreen", lw=0.6, alpha=0.6, label="id (true frame)")
    ax.set_ylabel("current [A]")
    ax.set_title("d-q currents: core's (in its estimated frame) and the plant's (true frame)",
                 fontsize=9)
    ax.legend(loc="upper left", fontsize=8, ncol=6)
    ax.grid(alpha=0.3)

    ax = axs[2]
    shade_states(ax, t, st)
    err = d["theta_err_deg"]
    run = d["outputs_on"] > 0.5
    ax.plot(t[run], err[run], color="tab:purple", lw=0.7, ls="none", marker=".", ms=1.5)
    cl = st == 4
    lim = 20.0
    if np.any(cl):
        lim = max(10.0, min(180.0, 1.3 * np.percentile(np.abs(err[cl]), 99.5)))
    ax.set_ylim(-lim, lim)
    ax.axhline(0, color="k", lw=0.5)
    ax.set_ylabel("angle error [deg el.]")
    ax.set_title("estimated - true electrical angle (outputs on; forced angle before "
                 "CLOSED_LOOP)", fontsize=9)
    ax.grid(alpha=0.3)

    ax = axs[3]
    ax.plot(t, d["ia_A"], lw=0.5, label="ia")
    ax.plot(t, d["ib_A"], lw=0.5, label="ib")
    ax.plot(t, d["ic_A"], lw=0.5, label="ic")
    ax.set_ylabel("phase current [A]")
    ax.set_title("phase currents (true, + = into the motor)", fontsize=9)
    ax.legend(loc="upper left", fontsize=8, ncol=3)
    ax.grid(alpha=0.3)

    ax = axs[4]
    for _k, n in enumerate(("a", "b", "c")):
        ax.plot(t, 100.0 * d["duty_" + n], lw=0.5, label="duty " + n)
    ax.set_ylabel("duty [%]")
    ax.set_ylim(-5, 105)
    ax.set_title("duties computed by the core (applied the next period)", fontsize=9)
    ax.legend(loc="upper left", fontsize=8, ncol=3)
    ax.grid(alpha=0.3)

    ax = axs[5]
    ax.step(t, st, where="post", color="k", lw=1.2, label="state")
    ax.set_yticks(range(len(names.states)))
    ax.set_yticklabels(names.states, fontsize=7)
    ax.set_ylim(-0.5, len(names.states) - 0.5)
    ax.set_xlabel("time [s]")
    faults = np.flatnonzero(np.diff(d["fault"]) > 0) + 1
    for i in faults:
        code = int(d["fault"][i])
        ax.annotate(names.fault(code), (t[i], st[i]),
                    xytext=(4, -12), textcoords="offset points", color="red", fontsize=8)
    ax2 = ax.twinx()
    ax2.plot(t, d["load_Nm"] * 1000.0, color="tab:brown", lw=1.0, label="load torque [mN m]")
    ax2.plot(t, d["torque_Nm"] * 1000.0, color="tab:olive", lw=0.5, alpha=0.6,
             label="motor torque [mN m]")
    ax2.set_ylabel("torque [mN m]")
    ax3 = ax.twinx()
    ax3.spines["right"].set_position(("axes", 1.09))
    ax3.plot(t, d["vbus_V"], color="tab:cyan", lw=0.8, label="bus [V]")
    ax3.set_ylabel("bus [V]", color="tab:cyan")
    lines = ax.get_lines()[:1] + ax2.get_lines() + ax3.get_lines()
    ax.legend(lines, [str(ln.get_label()) for ln in lines], loc="upper left", fontsize=8, ncol=4)
    ax.set_title("core state, torques and DC bus", fontsize=9)
    ax.grid(alpha=0.3)

    # ---- close-up -------------------------------------------------------
    z, is_zoom = zoom_window(d)
    tz = (t[z] - t[z][0]) * 1000.0
    label = "close-up at %.3f s%s" % (t[z][0], "" if is_zoom else " (end of run)")
    zax = fig.add_subplot(gs[0:2, 1])
    zax.plot(tz, d["theta_deg"][z], color="tab:blue", lw=1.2, label="true")
    zax.plot(tz, d["theta_est_deg"][z], color="tab:orange", lw=1.0, ls="--", label="estimated")
    zax.set_ylabel("electrical angle [deg]")
    zax.set_ylim(-190, 190)
    zax.set_yticks([-180, -90, 0, 90, 180])
    zr = zax.twinx()
    zr.plot(tz, d["theta_err_deg"][z], color="tab:purple", lw=0.8, label="est - true")
    zr.set_ylabel("est - true [deg]", color="tab:purple")
    e = d["theta_err_deg"][z]
    m = max(5.0, 1.5 * np.max(np.abs(e))) if e.size else 5.0
    zr.set_ylim(-m, m)
    lines = zax.get_lines() + zr.get_lines()
    zax.legend(lines, [str(ln.get_label()) for ln in lines], loc="lower left", fontsize=8)
    zax.set_title(label + ": estimated vs true angle", fontsize=9)
    zax.grid(alpha=0.3)

    zax = fig.add_subplot(gs[2:4, 1])
    for n in ("a", "b", "c"):
        zax.plot(tz, d["i%s_A" % n][z], lw=1.0, label="i" + n)
    zax.set_ylabel("phase current [A]")
    zax.set_title(label + ": phase currents", fontsize=9)
    zax.legend(loc="upper right", fontsize=8)
    zax.grid(alpha=0.3)

    zax = fig.add_subplot(gs[4:6, 1])
    for n in ("a", "b", "c"):
        zax.plot(tz, 100.0 * d["duty_" + n][z], lw=1.0, label="duty " + n)
    zax.set_ylabel("duty [%]")
    zax.set_xlabel("time from close-up start [ms]")
    zax.set_title(label + ": duties", fontsize=9)
    zax.legend(loc="upper right", fontsize=8)
    zax.grid(alpha=0.3)

    save(fig, args[1])
    return 0


if __name__ == "__main__":
    sys.exit(main())
