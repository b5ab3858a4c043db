"""tools/scope - live data monitor for the AN1078 firmware (board UART or `sim --pty`).

    .venv/bin/python tools/scope --port /dev/ttyUSB0 --list
    .venv/bin/python tools/scope --port /dev/pts/5 --channels speed_est,speed_ref,iq \\
        --start-rpm 2000                       # live plot, keys: g start, x stop, +/- 100 rpm
    .venv/bin/python tools/scope --port /dev/pts/5 --headless --start-rpm 2000 \\
        --duration 1 --csv run.csv --png run.png

docs/monitor.md describes the protocol and the options.
"""

import argparse
import csv
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import monproto as mp  # noqa: E402

DEFAULT_CHANNELS = "speed_est,speed_ref,iq,id"


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="tools/scope", description=__doc__.split("\n")[0])
    ap.add_argument("--port", required=True, help="serial port or pty (sim --pty prints it)")
    ap.add_argument("--baud", type=int, default=38400, help="UART rate (default 38400, HAL_UART_BAUD)")
    ap.add_argument("--list", action="store_true", help="list variables and parameters, then exit")
    ap.add_argument("--channels", default=DEFAULT_CHANNELS, help=f"comma-separated (default {DEFAULT_CHANNELS})")
    ap.add_argument("--decim", type=int, default=0,
                    help="PWM periods per sample (default: the smallest the baud rate carries, with margin)")
    ap.add_argument("--snapshot", action="store_true",
                    help="one full-rate snapshot into the device buffer instead of a stream")
    ap.add_argument("--start-rpm", type=float, help="set the speed reference (remote) and start the motor")
    ap.add_argument("--from-start", action="store_true",
                    help="headless: start recording first, then start the motor (records the start-up)")
    ap.add_argument("--settle", type=float, default=0.5,
                    help="with --start-rpm: seconds to wait after the reference is reached (default 0.5)")
    ap.add_argument("--start-timeout", type=float, default=20.0, help="seconds to reach closed loop")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="set a tuning parameter (repeatable)")
    ap.add_argument("--stop", action="store_true", help="stop the motor at the end")
    ap.add_argument("--headless", action="store_true", help="record, write CSV/PNG, no window")
    ap.add_argument("--duration", type=float, default=1.0, help="headless: seconds to record (default 1)")
    ap.add_argument("--window", type=float, default=2.0, help="live: seconds shown (default 2)")
    ap.add_argument("--csv", help="write the recorded samples here")
    ap.add_argument("--png", help="headless: write the plot here")
    ap.add_argument("--title", default="", help="plot title")
    return ap.parse_args(argv)


def open_port(args):
    import serial

    port = serial.Serial(args.port, args.baud, timeout=0.05)
    time.sleep(0.05)
    port.reset_input_buffer()
    return port


def print_list(mon):
    i = mon.info
    print(f"monitor v{i['version']}: {i['nvars']} variables, {i['nparams']} parameters, up to "
          f"{i['max_ch']} channels, buffer {i['buf_words']} words, PWM {i['f_pwm']} Hz")
    print("variables:")
    for v in mon.vars:
        scale = f"Q15 of {v.fs:g} {v.unit}" if v.kind == mp.KIND_Q15 else "integer"
        print(f"  {v.idx:2d} {v.name:14s} {scale}")
    print("parameters (SET_PARAM, Q15 mantissas):")
    for p in mon.params:
        print(f"  {p.idx:2d} {p.name:10s} = {p.value:6d}   range {p.min}..{p.max}")


def choose_decim(args, mon, nch):
    f_pwm = mon.info["f_pwm"]
    if args.decim > 0:
        return args.decim
    if args.snapshot:
        return 1
    limit = 0.8 * mp.max_rate(nch, args.baud)
    d = 1
    while f_pwm / d > limit:
        d += 1
    return d


def start_motor(args, mon):
    mon.run_motor(args.start_rpm)
    target = int(round(args.start_rpm * 32768.0 / mon.var("speed_ref").fs))
    t_end = time.monotonic() + args.start_timeout
    while True:
        st = mon.status()
        if st["state"] == mp.STATE_FAULT:
            raise mp.MonitorError(f"motor faulted (code {st['fault']})")
        if st["state"] == mp.STATE_CLOSED_LOOP and abs(st["speed_ref"] - target) <= 1:
            break
        if time.monotonic() > t_end:
            raise mp.MonitorError(f"no closed loop at {args.start_rpm} rpm within {args.start_timeout} s "
                                  f"(state {mp.STATES[st['state']]})")
        time.sleep(0.05)
    time.sleep(args.settle)


def record(args, mon, names, decim, after_start=None):
    """Headless recording: returns (index list, raw rows)."""
    f_pwm = mon.info["f_pwm"]
    mon.select(names, decim)
    want = max(1, int(round(args.duration * f_pwm / decim)))
    rows, idx = [], []
    expect = 0
    if args.snapshot:
        mon.start(mp.MODE_SNAPSHOT, mp.TRIG_NOW)
    else:
        mon.start(mp.MODE_STREAM, mp.TRIG_NOW)
    if after_start is not None:
        after_start()
    t_end = time.monotonic() + args.duration * 3 + 10
    done = False
    while not done and time.monotonic() < t_end:
        for flags, index, sets in mon.read_data(wait=0.05):
            if index != (expect & 0xFFFF):
                raise mp.MonitorError(f"samples lost: got index {index}, expected {expect & 0xFFFF}")
            for s in sets:
                idx.append(expect)
                rows.append(s)
                expect += 1
            if flags & mp.DATA_OVERFLOW:
                raise mp.MonitorError("the device stopped the stream: host too slow for this rate; "
                                      "raise --decim")
            if flags & mp.DATA_LAST:
                done = True
        if not args.snapshot and len(rows) >= want:
            done = True
    if not args.snapshot:
        mon.stop()
        rows, idx = rows[:want], idx[:want]
    if not done:
        raise mp.MonitorError("recording timed out")
    return idx, rows


def csv_row(i, decim, f_pwm, vs, raw):
    """Sample set i: index, time, the values in engineering units."""
    return [i, f"{i * decim / f_pwm:.6f}"] + [f"{v.to_eng(x):.6g}" for v, x in zip(vs, raw)]


def write_csv(path, mon, names, decim, idx, rows):
    f_pwm = mon.info["f_pwm"]
    vs = [mon.var(n) for n in names]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["index", "t_s"] + [f"{v.name}_{v.unit}" if v.unit else v.name for v in vs]
                   + [f"{v.name}_raw" for v in vs])
        for i, r in zip(idx, rows):
            w.writerow(csv_row(i, decim, f_pwm, vs, r) + list(r))


def plot(mon, names, decim, idx, rows, png, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    f_pwm = mon.info["f_pwm"]
    vs = [mon.var(n) for n in names]
    t = np.array(idx, dtype=float) * decim / f_pwm
    data = np.array(rows, dtype=float).reshape(len(rows), len(vs)) if rows else np.zeros((0, len(vs)))
    units = []
    for v in vs:
        if v.unit not in units:
            units.append(v.unit)
    fig, axes = plt.subplots(len(units), 1, sharex=True, figsize=(9, 2.4 * len(units) + 0.6), squeeze=False)
    for ax, u in zip(axes[:, 0], units):
        for k, v in enumerate(vs):
            if v.unit == u:
                ax.plot(t, [v.to_eng(x) for x in data[:, k]], label=v.name, lw=1.0)
        ax.set_ylabel(u or "value")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    axes[-1, 0].set_xlabel(f"time since the first sample (s); one sample every {decim} PWM periods "
                           f"({f_pwm / decim:g} Hz)")
    fig.suptitle(title or "tools/scope", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def live(args, mon, names, decim):
    import collections

    import matplotlib.pyplot as plt

    f_pwm = mon.info["f_pwm"]
    vs = [mon.var(n) for n in names]
    n_show = max(10, int(args.window * f_pwm / decim))
    buf_t = collections.deque(maxlen=n_show)
    buf = [collections.deque(maxlen=n_show) for _ in vs]
    out = open(args.csv, "w", newline="") if args.csv else None
    writer = csv.writer(out) if out else None
    if writer:
        writer.writerow(["index", "t_s"] + [v.name for v in vs])
    state = {"expect": 0, "rpm": args.start_rpm or 1000.0}
    mon.select(names, decim)
    mon.start()
    fig, ax = plt.subplots(len(vs), 1, sharex=True, squeeze=False)
    lines = []
    for a, v in zip(ax[:, 0], vs):
        (ln,) = a.plot([], [], lw=1.0)
        a.set_ylabel(f"{v.name} [{v.unit}]" if v.unit else v.name)
        a.grid(True, alpha=0.3)
        lines.append(ln)
    ax[-1, 0].set_xlabel("s")

    def on_key(ev):
        try:
            if ev.key == "g":
                mon.run_motor(state["rpm"])
            elif ev.key == "x":
                mon.motor(mp.MOTOR_STOP)
            elif ev.key in ("+", "-"):
                state["rpm"] += 100.0 if ev.key == "+" else -100.0
                mon.set_speed(state["rpm"])
        except mp.MonitorError as e:
            print(f"scope: {e}", file=sys.stderr)

    fig.canvas.mpl_connect("key_press_event", on_key)
    plt.ion()
    plt.show()
    try:
        while plt.fignum_exists(fig.number):
            for flags, index, sets in mon.read_data(wait=0.02):
                for s in sets:
                    i = state["expect"]
                    state["expect"] += 1
                    buf_t.append(i * decim / f_pwm)
                    for k, v in enumerate(vs):
                        buf[k].append(v.to_eng(s[k]))
                    if writer:
                        writer.writerow(csv_row(i, decim, f_pwm, vs, s))
                if flags & mp.DATA_OVERFLOW:
                    print("scope: overflow, restarting the stream", file=sys.stderr)
                    state["expect"] = 0
                    mon.start()
            for k, ln in enumerate(lines):
                ln.set_data(list(buf_t), list(buf[k]))
                ln.axes.relim()
                ln.axes.autoscale_view()
            fig.canvas.draw_idle()
            plt.pause(0.05)
    finally:
        mon.stop()
        if out:
            out.close()


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    port = open_port(args)
    mon = mp.Monitor(port)
    try:
        mon.connect()
        if args.list:
            print_list(mon)
            return 0
        names = [n for n in args.channels.split(",") if n]
        if not 1 <= len(names) <= mon.info["max_ch"]:
            raise mp.MonitorError(f"1..{mon.info['max_ch']} channels")
        for n in names:
            mon.var(n)
        try:
            mon.stop()  # a recording left running by an earlier session
        except mp.MonitorError:
            pass
        mon.read_data(wait=0.1)
        for s in args.set:
            name, _, val = s.partition("=")
            mon.set_param(name, int(val, 0))
        decim = choose_decim(args, mon, len(names))
        go = None
        if args.start_rpm is not None:
            if args.from_start and args.headless:
                def go():
                    mon.run_motor(args.start_rpm)
            else:
                start_motor(args, mon)
        if args.headless:
            idx, rows = record(args, mon, names, decim, go)
            f_pwm = mon.info["f_pwm"]
            print(f"scope: {len(rows)} samples of {','.join(names)} every {decim} periods "
                  f"({f_pwm / decim:g} Hz), {len(rows) * decim / f_pwm:.3f} s")
            if args.csv:
                write_csv(args.csv, mon, names, decim, idx, rows)
                print(f"scope: CSV {args.csv}")
            if args.png:
                plot(mon, names, decim, idx, rows, args.png, args.title)
                print(f"scope: PNG {args.png}")
        else:
            live(args, mon, names, decim)
        if args.stop:
            mon.motor(mp.MOTOR_STOP)
    except mp.MonitorError as e:
        print(f"scope: {e}", file=sys.stderr)
        return 1
    finally:
        port.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
