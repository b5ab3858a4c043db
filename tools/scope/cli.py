# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""an1078-scope (tools/scope): an X2Cscope client for the AN1078 firmware and `sim --pty`.

    an1078-scope --port /dev/pts/5 info
    an1078-scope --map x2cmap.yml list
    an1078-scope --port /dev/pts/5 --map x2cmap.yml read motor.smc.omega motor.state
    an1078-scope --port /dev/pts/5 --map x2cmap.yml write x2c.tune.speed_ref_rpm 1000
    an1078-scope --port /dev/pts/5 --map x2cmap.yml capture motor.smc.omega motor.i_dq.q \\
        --trigger motor.state --level 1 --delay 40 --then x2c.tune.run=1 --csv run.csv --png run.png
    an1078-scope --port tcp://127.0.0.1:12666 --map x2cmap.yml live motor.smc.omega

The map (--map) is the YAML an1078-x2cmap writes from the simulator's ELF (pyx2cscope's
import_variables format); engineering values are raw / 32768 x full scale where the map gives a
full scale, else the raw value. `write` takes the raw integer (`list` shows each tunable's range).
Every failure ends with one line on stderr, "scope: ...", and exit status 1 (2 for a usage
error); --csv and --png never replace an existing file without --force, and are written whole or
not at all.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import math
import os
import re
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, NoReturn

from scope import lnet, mc_names, x2c
from scope.varmap import MapError, Var, VarMap, load_map

if TYPE_CHECKING:
    from matplotlib.axes import Axes

EXIT_FAIL, EXIT_USAGE, EXIT_INTERRUPTED = 1, 2, 130
DEFAULT_PERIOD_US = 50.0  # the ADC interrupt's period at 20 kHz PWM: one scope call each


class UsageError(Exception):
    """A command line that cannot be carried out as asked (exit 2)."""


class _Parser(argparse.ArgumentParser):
    """argparse that refuses in one line, like every other failure of the tool."""

    def error(self, message: str) -> NoReturn:
        print(f"scope: {' '.join(message.split())} (an1078-scope --help)", file=sys.stderr)
        sys.exit(EXIT_USAGE)


def _whole(lo: int, hi: int) -> Callable[[str], int]:
    def conv(s: str) -> int:
        t = s.strip()
        if re.fullmatch(r"[+-]?[0-9]+", t) is None:
            raise argparse.ArgumentTypeError(f"{s!r} is not a whole number")
        v = int(t)
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{s!r} is outside {lo}..{hi}")
        return v

    return conv


def _number(lo: float, hi: float) -> Callable[[str], float]:
    def conv(s: str) -> float:
        try:
            v = float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{s!r} is not a number") from None
        if not math.isfinite(v) or not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{s!r} is outside {lo:g}..{hi:g}")
        return v

    return conv


def _capture_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("names", nargs="+", metavar="NAME", help="1..8 variables of the map")
    p.add_argument("--trigger", metavar="NAME", help="trigger on an edge of this variable")
    p.add_argument("--level", type=_number(-1e12, 1e12), metavar="X",
                   help="trigger level, engineering units when the map gives a full scale, else raw (default 0)")
    p.add_argument("--edge", choices=("rising", "falling"), help="trigger edge (default rising)")
    p.add_argument("--delay", type=_whole(-(1 << 24), 1 << 24), metavar="N",
                   help="datasets: N > 0 keeps N before the trigger, N < 0 waits N after it (default 0)")
    p.add_argument("--auto", action="store_true", help="trigger mode auto: fire at once")
    p.add_argument("--prescaler", type=_whole(0, 65535), default=0, metavar="N",
                   help="one dataset every N + 1 interrupt calls (default 0)")
    p.add_argument("--period-us", type=_number(0.001, 1e9), default=DEFAULT_PERIOD_US, metavar="US",
                   help=f"the scope's call period, µs (default {DEFAULT_PERIOD_US:g}: 20 kHz PWM)")
    p.add_argument("--timeout", type=_number(0.01, 86400), default=10.0, metavar="S",
                   help="seconds to wait for the capture (default 10)")


def parse_args(argv: list[str]) -> argparse.Namespace:
    ap = _Parser(prog="an1078-scope", description=__doc__,
                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--port", help="serial port, pty (sim --pty prints it) or tcp://HOST:PORT")
    ap.add_argument("--baud", type=_whole(50, 4_000_000), default=115200, help="UART rate, 8N1 (default 115200)")
    ap.add_argument("--map", metavar="FILE.yml", help="the variable map (an1078-x2cmap)")
    ap.add_argument("--reply-timeout", type=_number(0.01, 60), default=1.0, metavar="S",
                    help="seconds to wait for each reply (default 1)")
    sub = ap.add_subparsers(dest="cmd", metavar="CMD", parser_class=_Parser)
    sub.required = True
    sub.add_parser("info", help="the target's device info and scope state")
    sub.add_parser("list", help="the map's variables (no port needed)")
    p = sub.add_parser("read", help="read variables: raw and engineering value")
    p.add_argument("names", nargs="+", metavar="NAME")
    p = sub.add_parser("write", help="write a tunable (raw integer), read it back")
    p.add_argument("name", metavar="NAME")
    p.add_argument("value", metavar="VALUE")
    p = sub.add_parser("capture", help="one scope capture, printed, and to --csv / --png")
    _capture_options(p)
    p.add_argument("--then", action="append", default=[], metavar="NAME=VALUE",
                   help="write a tunable (raw) once the scope is armed, e.g. x2c.tune.run=1 to capture a start "
                        "(repeatable, in order)")
    p.add_argument("--csv", metavar="F", help="write the capture here (time and engineering values)")
    p.add_argument("--png", metavar="F", help="plot the capture here (a .png name)")
    p.add_argument("--force", action="store_true", help="replace an existing --csv / --png")
    p = sub.add_parser("live", help="repeated captures in a window")
    _capture_options(p)
    p.add_argument("--headless", action="store_true", help="no window: print --frames captures")
    p.add_argument("--frames", type=_whole(1, 1_000_000), default=3, help="with --headless: captures (default 3)")
    return ap.parse_args(argv)


# ---- output files ----------------------------------------------------------------------------


def check_output(path: str, opt: str, force: bool) -> None:
    if not path:
        raise UsageError(f"{opt}: empty file name")
    real = os.path.realpath(path)
    if os.path.lexists(path) or os.path.lexists(real):
        if not force:
            raise UsageError(f"{opt} {path!r} exists: not replaced (--force replaces it)")
        if not os.path.isfile(real):
            raise UsageError(f"{opt} {path!r} exists and is not a regular file")
        if not os.access(real, os.W_OK):
            raise UsageError(f"{opt} {path!r} is read-only")
    folder = os.path.dirname(real) or "."
    if not os.path.isdir(folder):
        raise UsageError(f"{opt} {path!r}: no folder {folder!r}")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise UsageError(f"{opt} {path!r}: cannot write in {folder!r}")


@contextlib.contextmanager
def replacing(path: str) -> Iterator[str]:
    """A temporary name beside path to write; renamed over path only when the block succeeds."""
    real = os.path.realpath(path)
    fd, tmp = tempfile.mkstemp(prefix=".scope-", suffix=".tmp", dir=os.path.dirname(real) or ".")
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, real)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


# ---- the map and the values ------------------------------------------------------------------


def need_map(args: argparse.Namespace) -> VarMap:
    if not args.map:
        raise UsageError(f"{args.cmd}: needs --map FILE.yml (an1078-x2cmap writes it from the simulator)")
    return load_map(args.map)


def lookup(vm: VarMap, name: str) -> Var:
    try:
        return vm.get(name)
    except MapError as e:
        raise UsageError(str(e)) from None


def eng_text(v: Var, raw: float) -> str:
    unit = f" {v.unit}" if v.unit else ""
    return f"{v.to_eng(raw):.6g}{unit}"


def decode(v: Var, b: bytes) -> int | float:
    return x2c.Channel(v.address, v.size, v.kind).decode(b)


def print_list(vm: VarMap) -> None:
    w = max(len(n) for n in vm.vars)
    print(f"{'name':{w}s}  address  {'type':17s}  {'access':16s}  unit")
    for v in vm.vars.values():
        scale = f" ({v.full_scale:g} {v.unit} = 32768)" if v.full_scale > 0 else ""
        unit = (v.unit + scale) if (v.unit or scale) else ("-" if vm.has_units else "")
        print(f"{v.name:{w}s}  0x{v.address:04X}   {v.type:17s}  {v.access:16s}  {unit}")


def parse_value(v: Var, s: str) -> int:
    t = s.strip().lower()
    try:
        raw = int(t, 0) if re.fullmatch(r"[+-]?(0x[0-9a-f]+|[0-9]+)", t) else None
    except ValueError:
        raw = None
    if raw is None:
        raise UsageError(f"write {v.name}: {s!r} is not a whole number (write takes the raw value)")
    lo, hi = v.raw_range
    if not lo <= raw <= hi:
        raise UsageError(f"write {v.name}: {raw} does not fit its {v.size} byte(s) ({lo}..{hi})")
    return raw


# ---- commands --------------------------------------------------------------------------------


def cmd_info(t: x2c.Target) -> None:
    i = t.info or t.device_info()
    st = t.scope_state()
    print(f"processor 0x{i.processor_id:04X} ({i.processor}): 16-bit addresses")
    print(f"monitor version {i.monitor_version}, application version {i.app_version}, frames up to "
          f"{i.max_frame} data bytes")
    print(f"monitor {i.monitor_date} {i.monitor_time}, application {i.app_date} {i.app_time}")
    print(f"DSP state 0x{i.dsp_state:02X} ({x2c.DSP_STATE_NAMES.get(i.dsp_state, 'unknown')})")
    print(f"scope: {st.state_name}, {st.channels} channel(s), prescaler {st.prescaler}, buffer {st.buffer_size} "
          f"bytes at 0x{st.buffer_address:04X} ({st.used_length} used), version 0x{st.version:02X}")


def named(v: Var, raw: int | float) -> str:
    """The core's name of a state or fault code (firmware/mc.h), else ""."""
    if v.name not in ("motor.state", "motor.fault") or not isinstance(raw, int):
        return ""
    try:
        names = mc_names.read()
    except (OSError, mc_names.McNamesError):
        return ""  # an installed copy without the firmware beside it: the number alone
    return f" ({names.state(raw) if v.name == 'motor.state' else names.fault(raw)})"


def cmd_read(t: x2c.Target, vs: list[Var]) -> None:
    w = max(len(v.name) for v in vs)
    for v in vs:
        raw = decode(v, t.read(v.address, v.size, v.size))
        print(f"{v.name:{w}s}  raw {raw}  = {eng_text(v, raw)}{named(v, raw)}")


def cmd_write(t: x2c.Target, v: Var, raw: int) -> int:
    try:
        write_checked(t, v, raw)
    except x2c.TargetError as e:
        back = ""
        with contextlib.suppress(lnet.LNetError):
            back = f"; it reads {decode(v, t.read(v.address, v.size, v.size))}"
        print(f"scope: write {v.name} = {raw}: refused with error 0x{e.code:02X} ({e.name}: "
              f"{x2c.ERROR_TEXT.get(e.code, 'unknown')}){back}", file=sys.stderr)
        return EXIT_FAIL
    back_raw = decode(v, t.read(v.address, v.size, v.size))
    print(f"{v.name}: wrote {raw}, reads back {back_raw} (= {eng_text(v, back_raw)})")
    return 0


def build_config(args: argparse.Namespace, vm: VarMap) -> tuple[x2c.ScopeConfig, list[Var]]:
    vs = [lookup(vm, n) for n in args.names]
    if not 1 <= len(vs) <= x2c.MAX_CHANNELS:
        raise UsageError(f"{args.cmd}: 1..{x2c.MAX_CHANNELS} channels, not {len(vs)}")
    chans = tuple(x2c.Channel(v.address, v.size, v.kind) for v in vs)
    ds = sum(v.size for v in vs)
    trig: x2c.Trigger | None = None
    if args.trigger is None and not args.auto:
        for opt, val in (("--level", args.level), ("--edge", args.edge), ("--delay", args.delay)):
            if val is not None:
                raise UsageError(f"{opt}: only with --trigger NAME or --auto")
    else:
        delay = args.delay or 0
        if not -(1 << 31) <= delay * ds < (1 << 31):
            raise UsageError(f"--delay {delay}: too many datasets")
        rising = args.edge != "falling"
        if args.trigger is None:
            if args.level is not None:
                raise UsageError("--level: only with --trigger NAME")
            trig = x2c.Trigger(0, 2, "U", 0, delay, rising, auto=True)
        else:
            tv = lookup(vm, args.trigger)
            level = 0.0 if args.level is None else args.level
            raw: int | float
            if tv.kind == "F":
                raw = tv.from_eng(level)
            else:
                exact = tv.from_eng(level)
                raw = round(exact)
                if tv.full_scale <= 0 and exact != raw:
                    raise UsageError(f"--level {level:g}: {tv.name} is an integer without a scale: a whole number")
                lo, hi = tv.raw_range
                if not lo <= raw <= hi:
                    raise UsageError(f"--level {level:g}: raw {raw} is outside {tv.name}'s {lo}..{hi}")
            trig = x2c.Trigger(tv.address, tv.size, tv.kind, raw, delay, rising, auto=args.auto)
    return x2c.ScopeConfig(chans, args.prescaler, trig), vs


def times(cap: x2c.Capture, dt: float) -> list[float]:
    """Seconds from the trigger (delay >= 0: the trigger dataset is 0; < 0: the first dataset is
    -delay datasets after it), or from the first dataset without a trigger."""
    t = cap.config.trigger
    first = 0 if t is None else -t.delay
    return [(first + i) * dt for i in range(len(cap.datasets))]


def eng_columns(cap: x2c.Capture, vs: list[Var]) -> list[list[float]]:
    return [[v.to_eng(x) for x in cap.channel(k)] for k, v in enumerate(vs)]


def progress_printer(enabled: bool = True) -> x2c.Progress:
    tty = sys.stderr.isatty()
    last = {"state": -1, "shown": 0.0}

    def show(st: x2c.ScopeState, elapsed: float) -> None:
        if not enabled:
            return
        if tty:
            end = "\n" if st.done else ""
            print(f"\rscope: capture: {st.state_name}, {elapsed:5.1f} s, {st.pointer}/{st.used_length} bytes"
                  f"\033[K", end=end, file=sys.stderr, flush=True)
        elif st.state != last["state"] or elapsed - last["shown"] >= 2.0:
            print(f"scope: capture: {st.state_name}, {elapsed:.1f} s, {st.pointer}/{st.used_length} bytes",
                  file=sys.stderr, flush=True)
            last["state"], last["shown"] = st.state, elapsed

    return show


def summary(cap: x2c.Capture, vs: list[Var], dt: float) -> list[str]:
    trig = cap.trigger_index
    lines = [f"captured {len(cap.datasets)} datasets of {cap.config.dataset_size} bytes, one every {dt * 1e6:g} µs"
             + (f", trigger at dataset {trig}" if trig is not None else "")
             + (f", starting {-cap.config.trigger.delay} datasets after the trigger"
                if cap.config.trigger is not None and cap.config.trigger.delay < 0 else "")]
    for v, col in zip(vs, eng_columns(cap, vs), strict=True):
        if col:
            lines.append(f"  {v.name}: min {min(col):.6g}, mean {sum(col) / len(col):.6g}, max {max(col):.6g}"
                         + (f" {v.unit}" if v.unit else ""))
    return lines


def write_csv(path: str, cap: x2c.Capture, vs: list[Var], dt: float) -> None:
    cols = eng_columns(cap, vs)
    with replacing(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["t_s"] + [f"{v.name}_{v.unit}" if v.unit else v.name for v in vs])
        for i, t in enumerate(times(cap, dt)):
            w.writerow([f"{t:.9g}"] + [f"{c[i]:.9g}" for c in cols])


def _plot(ax_list: list[Axes], cap: x2c.Capture, vs: list[Var], dt: float) -> None:
    t = times(cap, dt)
    cols = eng_columns(cap, vs)
    units = list(dict.fromkeys(v.unit for v in vs))
    for ax, u in zip(ax_list, units, strict=True):
        ax.clear()
        for v, col in zip(vs, cols, strict=True):
            if v.unit == u:
                ax.plot(t, col, label=v.name, lw=1.0)
        ax.set_ylabel(u or "value")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
        if cap.config.trigger is not None:
            ax.axvline(0.0, color="k", lw=0.6, ls="--")
    ax_list[-1].set_xlabel("s from the trigger" if cap.config.trigger is not None else "s from the first dataset")


def write_png(path: str, cap: x2c.Capture, vs: list[Var], dt: float, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(dict.fromkeys(v.unit for v in vs))
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(9, 2.4 * n + 0.6), squeeze=False)
    try:
        _plot(list(axes[:, 0]), cap, vs, dt)
        fig.suptitle(title, fontsize=10)
        fig.tight_layout()
        with replacing(path) as tmp:
            fig.savefig(tmp, dpi=100, format="png")  # format given: the name never chooses it
    finally:
        plt.close(fig)


def check_fits(t: x2c.Target, cfg: x2c.ScopeConfig) -> None:
    """A pre-trigger history the target's buffer cannot hold is a usage error, named as such
    (the target would only answer 0x42)."""
    st = t.scope_state()
    n = st.buffer_size // cfg.dataset_size
    if n == 0:
        raise UsageError(f"a dataset of {cfg.dataset_size} bytes does not fit the {st.buffer_size}-byte buffer")
    if cfg.trigger is not None and cfg.trigger.delay >= n:
        raise UsageError(f"--delay {cfg.trigger.delay}: the buffer holds {n} datasets of {cfg.dataset_size} bytes, "
                         f"so at most {n - 1} before the trigger")


def parse_then(vm: VarMap, items: list[str]) -> list[tuple[Var, int]]:
    out = []
    for item in items:
        name, eq, value = item.partition("=")
        if not eq:
            raise UsageError(f"--then {item!r}: want NAME=VALUE")
        v = lookup(vm, name.strip())
        out.append((v, parse_value(v, value)))
    return out


def write_checked(t: x2c.Target, v: Var, raw: int) -> None:
    t.write(v.address, v.size, raw.to_bytes(v.size, "little", signed=v.kind == "S" and raw < 0))


def cmd_capture(args: argparse.Namespace, t: x2c.Target, cfg: x2c.ScopeConfig, vs: list[Var],
                then: list[tuple[Var, int]]) -> None:
    dt = (args.prescaler + 1) * args.period_us * 1e-6
    check_fits(t, cfg)

    def armed_then_write() -> None:
        # the trigger is armed once the pre-trigger history is in: the pointer has passed it
        history = cfg.trigger.delay * cfg.dataset_size if cfg.trigger is not None else 0
        t_end = time.monotonic() + args.timeout
        last = 0
        while history > 0:
            st = t.scope_state()
            if st.pointer >= history or st.pointer < last or st.state != x2c.SCOPE_WAIT_TRIG:
                break  # past the history, or the ring wrapped already
            last = st.pointer
            if time.monotonic() > t_end:
                raise x2c.X2CError(f"capture: the scope did not record its {cfg.trigger.delay if cfg.trigger else 0} "
                                   f"datasets of history within {args.timeout:g} s")
            time.sleep(0.005)
        for v, raw in then:
            write_checked(t, v, raw)

    cap = t.capture(cfg, args.timeout, progress_printer(), after_start=armed_then_write if then else None)
    for ln in summary(cap, vs, dt):
        print(ln)
    if args.csv:
        write_csv(args.csv, cap, vs, dt)
        print(f"CSV {args.csv}")
    if args.png:
        write_png(args.png, cap, vs, dt, f"an1078-scope: {', '.join(v.name for v in vs)}")
        print(f"PNG {args.png}")


def cmd_live(args: argparse.Namespace, t: x2c.Target, cfg: x2c.ScopeConfig, vs: list[Var]) -> None:
    dt = (args.prescaler + 1) * args.period_us * 1e-6
    check_fits(t, cfg)
    if args.headless:
        for k in range(args.frames):
            cap = t.capture(cfg, args.timeout, None)
            cols = eng_columns(cap, vs)
            parts = [f"{v.name} {min(c):.6g}..{max(c):.6g}" + (f" {v.unit}" if v.unit else "")
                     for v, c in zip(vs, cols, strict=True) if c]
            print(f"frame {k + 1}: {len(cap.datasets)} datasets; " + "; ".join(parts), flush=True)
        return
    import matplotlib
    import matplotlib.pyplot as plt

    if os.name == "posix" and not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY") \
            and sys.platform != "darwin":
        raise UsageError("live: no display for a window (--headless runs without one)")
    n = len(dict.fromkeys(v.unit for v in vs))
    fig, axes = plt.subplots(n, 1, sharex=True, squeeze=False)
    fig.suptitle(f"an1078-scope live ({matplotlib.get_backend()}): close the window to stop", fontsize=9)
    plt.ion()
    plt.show()
    while plt.fignum_exists(fig.number):
        cap = t.capture(cfg, args.timeout, None)
        _plot(list(axes[:, 0]), cap, vs, dt)
        fig.canvas.draw_idle()
        plt.pause(0.05)


# ---- main ------------------------------------------------------------------------------------


def _fail(msg: str, code: int = EXIT_FAIL) -> int:
    print(f"scope: {' '.join(msg.split())}", file=sys.stderr)
    return code


Opener = Callable[[str, int], lnet.Transport]


def run(args: argparse.Namespace, opener: Opener = lnet.open_transport) -> int:
    # everything that needs no target is checked first: the map, the names, the files
    vm: VarMap | None = None
    if args.cmd != "info":
        vm = need_map(args)
    if args.cmd == "list":
        assert vm is not None
        print_list(vm)
        return 0
    vs: list[Var] = []
    cfg: x2c.ScopeConfig | None = None
    raw = 0
    if args.cmd == "read":
        assert vm is not None
        vs = [lookup(vm, n) for n in args.names]
    elif args.cmd == "write":
        assert vm is not None
        vs = [lookup(vm, args.name)]
        raw = parse_value(vs[0], args.value)
    elif args.cmd in ("capture", "live"):
        assert vm is not None
        cfg, vs = build_config(args, vm)
    then = parse_then(vm, args.then) if args.cmd == "capture" and vm is not None else []
    if args.cmd == "capture":
        if args.png is not None and not args.png.lower().endswith(".png"):
            raise UsageError(f"--png {args.png!r}: the name must end in .png")
        if args.csv is not None and args.png is not None and os.path.realpath(args.csv) == os.path.realpath(args.png):
            raise UsageError("--csv and --png name the same file")
        for path, opt in ((args.csv, "--csv"), (args.png, "--png")):
            if path is not None:
                check_output(path, opt, args.force)
    if not args.port:
        raise UsageError(f"{args.cmd}: needs --port (a serial port, a pty, or tcp://HOST:PORT)")
    link = lnet.Link(opener(args.port, args.baud), args.reply_timeout)
    try:
        t = x2c.Target(link)
        t.device_info()
        if args.cmd == "info":
            cmd_info(t)
        elif args.cmd == "read":
            cmd_read(t, vs)
        elif args.cmd == "write":
            return cmd_write(t, vs[0], raw)
        elif args.cmd == "capture":
            assert cfg is not None
            try:
                cmd_capture(args, t, cfg, vs, then)
            except KeyboardInterrupt:
                with contextlib.suppress(lnet.LNetError):
                    t.scope_stop()
                raise
        else:
            assert cfg is not None
            cmd_live(args, t, cfg, vs)
        return 0
    finally:
        link.close()


def main(argv: list[str] | None = None, opener: Opener = lnet.open_transport) -> int:
    """The command; opener makes the transport (tests hand in a fake one)."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        return run(args, opener)
    except UsageError as e:
        return _fail(str(e), EXIT_USAGE)
    except (lnet.LNetError, MapError) as e:
        return _fail(str(e))
    except ImportError as e:
        return _fail(f"{e.name or 'a package'} is not installed (run tools/bootstrap)")
    except BrokenPipeError:  # `list | head`: the reader left; nothing to say to it
        with contextlib.suppress(OSError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_FAIL
    except OSError as e:  # writing the CSV or the PNG
        return _fail(f"cannot write: {e.strerror or e}" + (f" ({e.filename})" if e.filename else ""))
    except KeyboardInterrupt:
        return _fail("interrupted", EXIT_INTERRUPTED)
    except Exception as e:  # never a traceback
        if os.environ.get("SCOPE_TRACEBACK"):
            raise
        return _fail(f"internal error, {type(e).__name__}: {' '.join(str(e).split())} (SCOPE_TRACEBACK=1 shows where)")


if __name__ == "__main__":
    sys.exit(main())
