"""tools/scope (scope.cli) - live data monitor for the AN1078 firmware (board UART or `sim --pty`).

    .venv/bin/python tools/scope --port /dev/ttyUSB0 --list
    .venv/bin/python tools/scope --port /dev/pts/5 --channels speed_est,speed_ref,iq \\
        --start-rpm 2000                       # live plot, keys: g start, x stop, +/- 100 rpm
    .venv/bin/python tools/scope --port /dev/pts/5 --headless --start-rpm 2000 \\
        --duration 1 --csv run.csv --png run.png

docs/monitor.md describes the protocol and the options. Every failure (a bad option, a port
that does not open, an output that cannot be written, a missing or corrupt reply) ends with one
line on stderr, "scope: ...", and exit status 1 (2 for a bad option); an output file is written
whole or not at all.
"""

import argparse
import csv
import math
import os
import re
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager, suppress
from typing import NoReturn

from scope import monproto as mp

DEFAULT_CHANNELS = "speed_est,speed_ref,iq,id"
EXIT_FAIL, EXIT_USAGE, EXIT_INTERRUPTED = 1, 2, 130

PortOpener = Callable[[argparse.Namespace], mp.Port]


class ScopeArgumentParser(argparse.ArgumentParser):
    """argparse that refuses in one line, like every other failure of the tool."""

    def error(self, message: str) -> NoReturn:
        print(f"scope: {' '.join(message.split())} (tools/scope --help)", file=sys.stderr)
        sys.exit(EXIT_USAGE)


def number(lo: float, hi: float, what: str) -> Callable[[str], float]:
    """An argparse type: a finite number in lo..hi (nan, inf and 1e300 never get through)."""

    def conv(s: str) -> float:
        try:
            v = float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{s!r} is not a number") from None
        if not math.isfinite(v) or not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{s!r} is outside {lo:g}..{hi:g} {what}")
        return v

    return conv


def whole(lo: int, hi: int, what: str) -> Callable[[str], int]:
    """An argparse type: a decimal whole number in lo..hi."""

    def conv(s: str) -> int:
        t = s.strip()
        if re.fullmatch(r"[+-]?[0-9]+", t) is None:
            raise argparse.ArgumentTypeError(f"{s!r} is not a whole number")
        v = int(t)
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{s!r} is outside {lo}..{hi} {what}")
        return v

    return conv


def parse_args(argv: list[str]) -> argparse.Namespace:
    ap = ScopeArgumentParser(prog="tools/scope", description=(__doc__ or "").split("\n")[0])
    ap.add_argument("--port", required=True, help="serial port or pty (sim --pty prints it)")
    ap.add_argument("--baud", type=whole(300, 4_000_000, "Bd"), default=38400,
                    help="UART rate (default 38400, HAL_UART_BAUD)")
    ap.add_argument("--list", action="store_true", help="list variables and parameters, then exit")
    ap.add_argument("--channels", default=DEFAULT_CHANNELS, help=f"comma-separated (default {DEFAULT_CHANNELS})")
    ap.add_argument("--decim", type=whole(0, mp.DECIM_MAX, "PWM periods"), default=0,
                    help="PWM periods per sample, 1..10000 (default 0: the smallest the baud rate carries, "
                         "with margin)")
    ap.add_argument("--snapshot", action="store_true",
                    help="one full-rate snapshot into the device buffer instead of a stream")
    ap.add_argument("--start-rpm", type=number(-32768, 32767, "rpm"),
                    help="set the speed reference (remote) and start the motor")
    ap.add_argument("--from-start", action="store_true",
                    help="headless: start recording first, then start the motor (records the start-up)")
    ap.add_argument("--settle", type=number(0, 60, "s"), default=0.5,
                    help="with --start-rpm: seconds to wait after the reference is reached (default 0.5)")
    ap.add_argument("--start-timeout", type=number(0.1, 600, "s"), default=20.0,
                    help="seconds to reach closed loop (default 20)")
    ap.add_argument("--reply-timeout", type=number(0.05, 10, "s"), default=1.0,
                    help="seconds to wait for each reply (default 1; a lost one is asked again when safe)")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="set a tuning parameter (repeatable)")
    ap.add_argument("--stop", action="store_true", help="stop the motor at the end (and on a failure)")
    ap.add_argument("--headless", action="store_true", help="record, write CSV/PNG, no window")
    ap.add_argument("--duration", type=number(0.001, 3600, "s"), default=1.0,
                    help="headless: seconds to record (default 1)")
    ap.add_argument("--window", type=number(0.01, 600, "s"), default=2.0, help="live: seconds shown (default 2)")
    ap.add_argument("--csv", help="write the recorded samples here")
    ap.add_argument("--png", help="headless: write the plot here (a .png name)")
    ap.add_argument("--title", default="", help="plot title")
    return ap.parse_args(argv)


def parse_sets(items: list[str]) -> list[tuple[str, int]]:
    out = []
    for s in items:
        name, eq, val = s.partition("=")
        v = int(val) if re.fullmatch(r"[+-]?[0-9]{1,6}", val.strip()) else None
        if not eq or not name or v is None:
            raise mp.MonitorError(f"--set {s!r}: want NAME=VALUE with a decimal whole number")
        if not -32768 <= v <= 32767:
            raise mp.MonitorError(f"--set {s!r}: {v} is outside the parameters' 16-bit range")
        out.append((name, v))
    return out


# ---- output files: checked before the device is touched, written whole or not at all ----

def check_output(path: str, opt: str) -> str | None:
    """Why path cannot be written (one line), or None. Only a regular file, or a new name in an
    existing writable folder: the tool never replaces a device, a folder or a read-only file."""
    if not path:
        return f"{opt}: empty file name"
    real = os.path.realpath(path)
    folder = os.path.dirname(real) or "."
    if os.path.lexists(real) and not os.path.isfile(real):
        return f"{opt} {path!r}: exists and is not a regular file"
    if os.path.isfile(real) and not os.access(real, os.W_OK):
        return f"{opt} {path!r}: exists and is read-only"
    if not os.path.isdir(folder):
        return f"{opt} {path!r}: no folder {folder!r}"
    if not os.access(folder, os.W_OK | os.X_OK):
        return f"{opt} {path!r}: cannot write in {folder!r}"
    return None


def check_outputs(args: argparse.Namespace) -> str | None:
    if args.png is not None and not args.headless:
        return "--png: only with --headless (the live plot is a window)"
    if args.png is not None and not args.png.lower().endswith(".png"):
        # matplotlib would pick the format from the name, or add ".png" to it: a file not asked for
        return f"--png {args.png!r}: the name must end in .png"
    for path, opt in ((args.csv, "--csv"), (args.png, "--png")):
        if path is not None:
            why = check_output(path, opt)
            if why is not None:
                return why
    if args.csv is not None and args.png is not None and os.path.realpath(args.csv) == os.path.realpath(args.png):
        return "--csv and --png name the same file"
    return None


@contextmanager
def replacing(path: str) -> Iterator[str]:
    """A temporary name beside path for the block to write; renamed over path only when the block
    ends without an exception: a failure leaves path as it was (and no temporary behind)."""
    real = os.path.realpath(path)
    fd, tmp = tempfile.mkstemp(prefix=".scope-", suffix=".tmp", dir=os.path.dirname(real) or ".")
    os.close(fd)
    try:
        mode = os.stat(real).st_mode & 0o777  # a file replaced keeps its mode
    except OSError:
        umask = os.umask(0)  # a new one gets what open() would give it (mkstemp's is 0600)
        os.umask(umask)
        mode = 0o666 & ~umask
    try:
        yield tmp
        os.chmod(tmp, mode)
        os.replace(tmp, real)
    except BaseException:
        with suppress(OSError):
            os.unlink(tmp)
        raise


def open_port(args: argparse.Namespace) -> mp.Port:
    import serial

    port = serial.Serial(args.port, args.baud, timeout=0.05)
    time.sleep(0.05)
    port.reset_input_buffer()
    return port


def print_list(mon: mp.Monitor) -> None:
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


def choose_decim(args: argparse.Namespace, mon: mp.Monitor, nch: int) -> int:
    f_pwm = mon.info["f_pwm"]
    if args.decim > 0:
        return int(args.decim)
    if args.snapshot:
        return 1
    limit = 0.8 * mp.max_rate(nch, args.baud)
    # the smallest d with f_pwm / d <= limit, found from its closed form and nudged by one
    d = max(1, math.ceil(f_pwm / limit))
    while d > 1 and f_pwm / (d - 1) <= limit:
        d -= 1
    while f_pwm / d > limit:
        d += 1
    if d > mp.DECIM_MAX:
        raise mp.MonitorError(f"{args.baud} Bd cannot carry {nch} channels at any decimation up to {mp.DECIM_MAX}")
    return d


def start_motor(args: argparse.Namespace, mon: mp.Monitor) -> None:
    fs = mon.var("speed_ref").fs  # before the start: a device without it is refused with the motor still
    target = round(args.start_rpm * 32768.0 / fs) if fs else 0
    mon.run_motor(args.start_rpm)
    t_end = time.monotonic() + args.start_timeout
    while True:
        st = mon.status()
        if st["state"] == mp.STATE_FAULT:
            raise mp.MonitorError(f"motor faulted (code {st['fault']})")
        if st["state"] == mp.STATE_CLOSED_LOOP and abs(st["speed_ref"] - target) <= 1:
            break
        if time.monotonic() > t_end:
            raise mp.MonitorError(f"no closed loop at {args.start_rpm} rpm within {args.start_timeout} s "
                                  f"(state {mp.state_name(st['state'])})")
        time.sleep(0.05)
    time.sleep(args.settle)


def record(args: argparse.Namespace, mon: mp.Monitor, names: list[str], decim: int,
           after_start: Callable[[], None] | None = None) -> tuple[list[int], list[tuple[int, ...]]]:
    """Headless recording: returns (index list, raw rows)."""
    f_pwm = mon.info["f_pwm"]
    mon.select(names, decim)
    want = max(1, round(args.duration * f_pwm / decim))
    rows: list[tuple[int, ...]] = []
    idx: list[int] = []
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


def csv_row(i: int, decim: int, f_pwm: int, vs: list[mp.Var], raw: tuple[int, ...]) -> list[object]:
    """Sample set i: index, time, the values in engineering units."""
    return [i, f"{i * decim / f_pwm:.6f}"] + [f"{v.to_eng(x):.6g}" for v, x in zip(vs, raw, strict=True)]


def write_csv(path: str, mon: mp.Monitor, names: list[str], decim: int, idx: list[int],
              rows: list[tuple[int, ...]]) -> None:
    f_pwm = mon.info["f_pwm"]
    vs = [mon.var(n) for n in names]
    with replacing(path) as tmp, open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["index", "t_s"] + [f"{v.name}_{v.unit}" if v.unit else v.name for v in vs]
                   + [f"{v.name}_raw" for v in vs])
        for i, r in zip(idx, rows, strict=True):
            w.writerow(csv_row(i, decim, f_pwm, vs, r) + list(r))


def plot(mon: mp.Monitor, names: list[str], decim: int, idx: list[int], rows: list[tuple[int, ...]],
         png: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    f_pwm = mon.info["f_pwm"]
    vs = [mon.var(n) for n in names]
    t = np.array(idx, dtype=float) * decim / f_pwm
    data = np.array(rows, dtype=float).reshape(len(rows), len(vs)) if rows else np.zeros((0, len(vs)))
    units: list[str] = []
    for v in vs:
        if v.unit not in units:
            units.append(v.unit)
    fig, axes = plt.subplots(len(units), 1, sharex=True, figsize=(9, 2.4 * len(units) + 0.6), squeeze=False)
    for ax, u in zip(axes[:, 0], units, strict=True):
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
    try:
        with replacing(png) as tmp:
            fig.savefig(tmp, dpi=100, format="png")  # format given: the name never chooses it
    finally:
        plt.close(fig)


def live(args: argparse.Namespace, mon: mp.Monitor, names: list[str], decim: int) -> None:
    import collections

    import matplotlib.pyplot as plt

    f_pwm = mon.info["f_pwm"]
    vs = [mon.var(n) for n in names]
    n_show = max(10, int(args.window * f_pwm / decim))
    buf_t: collections.deque[float] = collections.deque(maxlen=n_show)
    buf = [collections.deque[float](maxlen=n_show) for _ in vs]
    state = {"expect": 0, "rpm": args.start_rpm if args.start_rpm is not None else 1000.0}
    mon.select(names, decim)
    mon.start()
    fig, ax = plt.subplots(len(vs), 1, sharex=True, squeeze=False)
    lines = []
    for a, v in zip(ax[:, 0], vs, strict=True):
        (ln,) = a.plot([], [], lw=1.0)
        a.set_ylabel(f"{v.name} [{v.unit}]" if v.unit else v.name)
        a.grid(True, alpha=0.3)
        lines.append(ln)
    ax[-1, 0].set_xlabel("s")

    def on_key(ev: object) -> None:
        key = getattr(ev, "key", None)
        try:
            if key == "g":
                mon.run_motor(state["rpm"])
            elif key == "x":
                mon.motor(mp.MOTOR_STOP)
            elif key in ("+", "-"):
                state["rpm"] += 100.0 if key == "+" else -100.0
                mon.set_speed(state["rpm"])
        except mp.MonitorError as e:
            print(f"scope: {e}", file=sys.stderr)

    fig.canvas.mpl_connect("key_press_event", on_key)
    plt.ion()
    plt.show()
    with ExitStack() as stack:
        writer = None
        if args.csv:
            out = stack.enter_context(open(stack.enter_context(replacing(args.csv)), "w", newline=""))
            writer = csv.writer(out)
        if writer:
            writer.writerow(["index", "t_s"] + [v.name for v in vs])
        try:
            while plt.fignum_exists(fig.number):
                for flags, _index, sets in mon.read_data(wait=0.02):
                    for s in sets:
                        i = int(state["expect"])
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
            with suppress(mp.MonitorError):  # the error that ended the loop is the one to report
                mon.stop()


def session(args: argparse.Namespace, mon: mp.Monitor) -> int:
    """Everything after the port is open. Raises MonitorError on any failure."""
    mon.connect()
    if args.list:
        print_list(mon)
        return 0
    names = [n for n in args.channels.split(",") if n]
    if not 1 <= len(names) <= mon.info["max_ch"]:
        raise mp.MonitorError(f"--channels: 1..{mon.info['max_ch']} channels")
    for n in names:
        mon.var(n)
    with suppress(mp.MonitorError):
        mon.stop()  # a recording left running by an earlier session
    mon.read_data(wait=0.1)
    for name, value in parse_sets(args.set):
        mon.set_param(name, value)
    decim = choose_decim(args, mon, len(names))
    go = None
    if args.start_rpm is not None:
        if args.from_start and args.headless:
            def go() -> None:
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
    return 0


def _fail(msg: str, code: int = EXIT_FAIL) -> int:
    print(f"scope: {' '.join(msg.split())}", file=sys.stderr)
    return code


def main(argv: list[str] | None = None, opener: PortOpener = open_port) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        parse_sets(args.set)  # a malformed --set is a usage error: refused before the port opens
    except mp.MonitorError as e:
        return _fail(str(e), EXIT_USAGE)
    why = check_outputs(args)
    if why is not None:
        return _fail(why, EXIT_USAGE)
    try:
        port = opener(args)
    except ImportError as e:
        return _fail(f"pyserial is missing ({e}): run tools/bootstrap")
    except (OSError, ValueError) as e:  # pyserial's SerialException is an OSError
        return _fail(f"cannot open port {args.port!r}: {mp.one_line(e)}")
    mon = mp.Monitor(port, timeout=args.reply_timeout)
    try:
        return session(args, mon)
    except mp.MonitorError as e:
        if args.stop:
            with suppress(mp.MonitorError):  # the motor must not run on because the recording failed
                mon.motor(mp.MOTOR_STOP)
        return _fail(str(e))
    except OSError as e:  # writing the CSV or the PNG
        return _fail(f"cannot write: {mp.one_line(e)}")
    except KeyboardInterrupt:
        return _fail("interrupted", EXIT_INTERRUPTED)
    except Exception as e:
        if os.environ.get("SCOPE_TRACEBACK"):
            raise
        return _fail(f"internal error, {type(e).__name__}: {e} (SCOPE_TRACEBACK=1 shows where)")
    finally:
        close = getattr(port, "close", None)
        if close is not None:
            with suppress(OSError, ValueError):
                close()


if __name__ == "__main__":
    sys.exit(main())
