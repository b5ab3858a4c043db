"""End-to-end: the simulator serves the monitor protocol on a pseudo-terminal, tools/scope --headless
selects channels, starts the motor at 2000 rpm through the protocol, records 1 s; the recorded
estimated speed is compared with the simulator's true speed at the same PWM periods.

usage: e2e_scope.py <sim executable> <repo root> <output dir>
Exit status 77 (CTest: skipped, with the reason on stdout) without a pseudo-terminal or
without the venv's pyserial and matplotlib.
"""

from __future__ import annotations

import csv
import importlib.util
import math
import os
import signal
import subprocess
import sys
import time
from typing import NoReturn

RPM = 2000.0
TOL = 0.01  # 1 %
SKIP = 77  # CTest SKIP_RETURN_CODE (test/monitor/CMakeLists.txt)


def fail(msg: str) -> NoReturn:
    print(f"FAIL: {msg}")
    sys.exit(1)


def skip_without_tools() -> None:
    why = [f"{m} is not installed (run tools/bootstrap)" for m in ("serial", "matplotlib")
           if importlib.util.find_spec(m) is None]
    if not os.path.exists("/dev/ptmx"):
        why.append("no pseudo-terminals here (/dev/ptmx)")
    if why:
        print(f"SKIPPED: {'; '.join(why)}")
        sys.exit(SKIP)


def main() -> None:
    skip_without_tools()
    sim, root, out = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(out, exist_ok=True)
    truth_path = os.path.join(out, "e2e_truth.csv")
    scope_csv = os.path.join(out, "e2e_scope.csv")
    scope_png = os.path.join(out, "e2e_scope.png")
    for p in (truth_path, scope_csv, scope_png):
        if os.path.exists(p):
            os.remove(p)
    t0 = time.monotonic()
    # 2x real time: the start-up takes ~2 s of simulated time; the UART is emulated in simulated time.
    proc = subprocess.Popen([sim, "--pty", "--realtime", "2", "--truth", truth_path, "--duration", "60"],
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    try:
        line = proc.stdout.readline()
        if not line.startswith("pty: "):
            fail(f"sim did not print its pty: {line!r}")
        pty = line.split()[1]
        print(f"sim on {pty}")
        cmd = [sys.executable, os.path.join(root, "tools", "scope"), "--port", pty, "--headless",
               "--channels", "speed_est,speed_ref,iq,state", "--start-rpm", str(int(RPM)),
               "--duration", "1", "--csv", scope_csv, "--png", scope_png, "--stop",
               "--title", "e2e: tools/scope against sim --pty, 2000 rpm"]
        r = subprocess.run(cmd, timeout=60)
        if r.returncode != 0:
            fail(f"tools/scope exited with {r.returncode}")
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            tail = proc.communicate(timeout=10)[0]
        except subprocess.TimeoutExpired:
            proc.kill()
            tail = ""
        print(tail.strip())
    wall = time.monotonic() - t0

    with open(scope_csv) as f:
        rows = list(csv.DictReader(f))
    with open(truth_path) as f:
        truth = list(csv.DictReader(f))
    if not rows or not truth:
        fail("no samples")
    last_rec = truth[-1]["rec"]
    by_index = {int(t["index"]): t for t in truth if t["rec"] == last_rec}
    n = len(rows)
    dur = float(rows[-1]["t_s"]) - float(rows[0]["t_s"])
    if n < 100 or dur < 0.99:
        fail(f"only {n} samples over {dur:.3f} s")
    est: list[float] = []
    true: list[float] = []
    rel: list[float] = []
    for row in rows:
        i = int(row["index"])
        if i not in by_index:
            fail(f"sample {i} not in the simulator's log of recorded samples")
        t = by_index[i]
        e_rpm = float(row["speed_est_rpm"])
        # lossless: the recorded value is the core's speed_est of that very period
        if abs(e_rpm - float(t["speed_est_rpm"])) > 0.01:
            fail(f"sample {i}: recorded {e_rpm} rpm, the core had {t['speed_est_rpm']} rpm")
        if int(row["state_raw"]) != 4 or int(t["state"]) != 4:
            fail(f"sample {i}: not in closed loop")
        est.append(e_rpm)
        true.append(float(t["speed_true_rpm"]))
        rel.append((e_rpm - true[-1]) / true[-1])
    m_est, m_true = sum(est) / n, sum(true) / n
    rms = math.sqrt(sum(x * x for x in rel) / n)
    worst = max(abs(x) for x in rel)
    print(f"measured: {n} samples over {dur:.3f} s, all bit-exact with the core's speed_est of the same period")
    print(f"measured: mean recorded speed_est {m_est:.2f} rpm, mean true speed {m_true:.2f} rpm: "
          f"{100 * (m_est - m_true) / m_true:+.3f} % (limit 1 %)")
    print(f"measured: per-sample estimated vs true: rms {100 * rms:.3f} % (limit 1 %), "
          f"worst {100 * worst:.3f} % (estimator ripple at the sampled instant)")
    print(f"measured: true speed {m_true:.2f} rpm vs the 2000 rpm reference: "
          f"{100 * (m_true - RPM) / RPM:+.3f} %")
    print(f"measured: wall time {wall:.1f} s")
    if abs(m_est - m_true) > TOL * m_true:
        fail("mean estimated speed off by more than 1 %")
    if rms > TOL:
        fail("rms per-sample error above 1 %")
    if abs(m_true - RPM) > TOL * RPM:
        fail("the motor does not run at 2000 rpm")
    if not os.path.getsize(scope_png) > 10000:
        fail("no PNG")
    print("PASS")


if __name__ == "__main__":
    main()
