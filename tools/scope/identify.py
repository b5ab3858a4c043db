# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""an1078-identify (tools/scope): measure the motor on the board, or on `sim --pty`, and write
the motor description tools/tune takes.

    an1078-identify --port /dev/ttyUSB0 --map board_vars.yml --name mymotor --board mclv \\
        --rated-current 1.6 --rated-speed 3000 -o mymotor.toml
    tools/tune/tune mymotor.toml          # firmware/motors/motor_mymotor.h

It asks the firmware's X2Cscope target to identify the motor (x2c.tune.identify = 1: from
STOPPED only, the motor's rotor free to turn), waits for the result (x2c.id.*), and writes
[motor]: pole pairs, per-phase resistance and inductance, the peak line-to-line back-EMF
constant and, when measured, the inertia; the rated current and speed are the nameplate's,
given here, as no measurement gives them. The measured Ld, Lq and the inverter's dead time are
written as comments. Ke and J come from the firmware computed with its build's pole pairs; with
--pole-pairs P (the motor's, when the build's differ) they are scaled by P / p and (P / p)^2.
--no-run writes the result of the identification the target last ran, without a new one.

A failed identification writes nothing and says why in one line: the core's error
(firmware/mc_id.h MC_ID_ERROR_LIST: OPEN_PHASE, ROTOR_LOCKED, TOO_SMALL, ...). Every failure
is one line on stderr, "identify: ...", exit status 1 (2 for a usage error); -o never replaces
an existing file without --force and is written whole or not at all.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import NoReturn

from scope import lnet, mc_names, x2c
from scope.cli import UsageError, _number, check_output, replacing
from scope.varmap import MapError, Var, VarMap, load_map

EXIT_FAIL, EXIT_USAGE, EXIT_INTERRUPTED = 1, 2, 130
POLL_S = 0.1
STATUS_NONE, STATUS_RUNNING, STATUS_DONE, STATUS_FAILED = 0, 1, 2, 3  # mc.h mc_id_status_t
ID_FIELDS = ("status", "error", "rs_uohm", "ls_nh", "ke_uv_per_rpm", "j_ng_m2", "deadtime_ns", "ld_nh", "lq_nh",
             "pole_pairs")
BOARDS = ("mclv", "mchv")
NAME_RE = re.compile(r"[a-z][a-z0-9_]{0,31}")


class _Parser(argparse.ArgumentParser):
    """argparse that refuses in one line, like every other failure of the tool."""

    def error(self, message: str) -> NoReturn:
        print(f"identify: {' '.join(message.split())} (an1078-identify --help)", file=sys.stderr)
        sys.exit(EXIT_USAGE)


def _pole_pairs(s: str) -> int:
    if re.fullmatch(r"[0-9]+", s.strip()) is None or not 1 <= int(s) <= 50:
        raise argparse.ArgumentTypeError(f"{s!r} is not a whole number in 1..50")
    return int(s)


def _name(s: str) -> str:
    if NAME_RE.fullmatch(s) is None:
        raise argparse.ArgumentTypeError(f"{s!r}: lower-case letters, digits and _, starting with a letter, "
                                         "at most 32 (it names motor_<name>.h)")
    return s


def parse_args(argv: list[str]) -> argparse.Namespace:
    ap = _Parser(prog="an1078-identify", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--port", required=True, help="serial port, pty (sim --pty prints it) or tcp://HOST:PORT")
    ap.add_argument("--baud", type=int, default=115200, help="UART rate, 8N1 (default 115200)")
    ap.add_argument("--map", required=True, metavar="FILE.yml", help="the variable map (an1078-x2cmap)")
    ap.add_argument("--reply-timeout", type=_number(0.01, 60), default=1.0, metavar="S",
                    help="seconds to wait for each reply (default 1)")
    ap.add_argument("--timeout", type=_number(1, 3600), default=120.0, metavar="S",
                    help="seconds the identification may take (default 120)")
    ap.add_argument("--no-run", action="store_true", help="write the last identification's result, start none")
    ap.add_argument("--name", required=True, type=_name, help="the motor's name (motor_<name>.h)")
    ap.add_argument("--description", default="", help="one line for MOTOR_NAME (default: the name, measured)")
    ap.add_argument("--board", required=True, choices=BOARDS, help="the board the profile is for")
    ap.add_argument("--rated-current", required=True, type=_number(0.001, 1000), metavar="A",
                    help="the motor's rated current, peak A (the nameplate's)")
    ap.add_argument("--rated-speed", required=True, type=_number(1, 200000), metavar="RPM",
                    help="the motor's rated speed, rpm (the nameplate's)")
    ap.add_argument("--peak-current", type=_number(0.001, 1000), metavar="A",
                    help="short-term current allowed (field weakening), peak A")
    ap.add_argument("--pole-pairs", type=_pole_pairs, metavar="P",
                    help="the motor's pole pairs (default: the firmware build's)")
    ap.add_argument("-o", "--output", required=True, metavar="FILE.toml", help="the description to write")
    ap.add_argument("--force", action="store_true", help="replace an existing -o file")
    return ap.parse_args(argv)


@dataclass(frozen=True)
class Result:
    """x2c.id.*, raw (mc.h mc_id_result_t)."""

    status: int
    error: int
    rs_uohm: int
    ls_nh: int
    ke_uv_per_rpm: int
    j_ng_m2: int
    deadtime_ns: int
    ld_nh: int
    lq_nh: int
    pole_pairs: int


def _vars(vm: VarMap) -> dict[str, Var]:
    names = ["x2c.tune.identify", "motor.state", "motor.fault"] + [f"x2c.id.{f}" for f in ID_FIELDS]
    try:
        return {n: vm.get(n) for n in names}
    except MapError as e:
        raise UsageError(f"{e} (a map of a firmware without identification?)") from None


def _read(t: x2c.Target, v: Var) -> int:
    raw = x2c.Channel(v.address, v.size, v.kind).decode(t.read(v.address, v.size, v.size))
    return int(raw)


def read_result(t: x2c.Target, vs: dict[str, Var]) -> Result:
    return Result(*(_read(t, vs[f"x2c.id.{f}"]) for f in ID_FIELDS))


def run_identification(t: x2c.Target, vs: dict[str, Var], names: mc_names.McNames, timeout: float,
                       clock: Callable[[], float] = time.monotonic,
                       sleep: Callable[[float], None] = time.sleep) -> None:
    """Starts one identification and waits until the core is back in STOPPED (or FAULT) with a
    final status."""
    stopped, fault = names.states.index("STOPPED"), names.states.index("FAULT")
    measuring = {names.states.index("CALIBRATE"), names.states.index("IDENTIFY")}
    state = _read(t, vs["motor.state"])
    if state != stopped:
        raise UsageError(f"the motor is {names.state(state)}: identification starts from STOPPED only "
                         "(stop it, clear a fault with START then STOP)")
    v = vs["x2c.tune.identify"]
    try:
        t.write(v.address, v.size, (1).to_bytes(v.size, "little"))
    except x2c.TargetError as e:
        raise UsageError(f"the target refused the identification ({e.name}): not STOPPED, or the fault "
                         "pin still set") from None
    t0 = clock()
    seen = False
    while True:
        sleep(POLL_S)
        state = _read(t, vs["motor.state"])
        status = _read(t, vs["x2c.id.status"])
        seen = seen or state in measuring or status == STATUS_RUNNING
        if state in (stopped, fault) and status in (STATUS_DONE, STATUS_FAILED) and \
                (seen or clock() - t0 > 1.0):
            return
        if clock() - t0 > timeout:
            t.write(v.address, v.size, (0).to_bytes(v.size, "little"))
            raise lnet.LNetError(f"no result within {timeout:g} s (state {names.state(state)}): stopped it")


# The largest code of each field's type (mc.h mc_id_result_t: 32-bit values, 8-bit pole pairs):
# what a saturated conversion or an unwritten result reads as, never a measurement.
_SATURATED = {"rs_uohm": 0xFFFFFFFF, "ls_nh": 0xFFFFFFFF, "ke_uv_per_rpm": 0xFFFFFFFF, "j_ng_m2": 0xFFFFFFFF,
              "deadtime_ns": 0xFFFFFFFF, "ld_nh": 0xFFFFFFFF, "lq_nh": 0xFFFFFFFF}
LS_TOL = 0.05  # the mean inductance against (Ld + Lq) / 2: the firmware forms one from the others
DEADTIME_MAX_NS = 20_000  # 10 % of a 5 kHz PWM period: no inverter loses more


def judge(r: Result, state: str, fault: int, fault_name: str = "") -> None:
    """A result becomes a description only when it is a finished, fault-free, physically possible
    measurement: LNetError naming what is not."""
    if r.status != STATUS_DONE:
        return  # the caller says why (failed, or none)
    if r.error != 0:
        raise lnet.LNetError(f"the result says DONE with error code {r.error}: not a finished measurement")
    if state == "FAULT" or fault != 0:
        raise lnet.LNetError(f"the motor is {state} (fault {fault_name or fault}) after the identification: its "
                             "numbers are not trusted")
    if not 1 <= r.pole_pairs <= 50:
        raise lnet.LNetError(f"pole pairs {r.pole_pairs}: not a motor's (1..50)")
    for f, top in _SATURATED.items():
        v = getattr(r, f)
        if v >= top:
            raise lnet.LNetError(f"{f} {v:#x}: the code of a saturated or unwritten value, not a measurement")
    for f in ("rs_uohm", "ls_nh", "ld_nh", "lq_nh", "ke_uv_per_rpm"):
        if getattr(r, f) <= 0:
            raise lnet.LNetError(f"{f} {getattr(r, f)}: a motor has more than 0")
    mean = (r.ld_nh + r.lq_nh) / 2.0
    if abs(r.ls_nh - mean) > LS_TOL * mean:
        raise lnet.LNetError(f"inductance {r.ls_nh} nH against Ld {r.ld_nh} and Lq {r.lq_nh} nH: the mean "
                             f"must be within {LS_TOL:.0%} of (Ld + Lq) / 2 (one of them is corrupt)")
    if not 0 < r.deadtime_ns <= DEADTIME_MAX_NS:
        raise lnet.LNetError(f"dead time {r.deadtime_ns} ns: outside (0, {DEADTIME_MAX_NS}] ns")


def describe(r: Result, args: argparse.Namespace) -> str:
    """The tools/tune description of a finished identification."""
    p = args.pole_pairs or r.pole_pairs
    k = p / r.pole_pairs
    ke = r.ke_uv_per_rpm * 1e-3 * k  # uV/rpm = mV/krpm; V/krpm
    j = r.j_ng_m2 * 1e-9 * k * k
    desc = args.description or f"{args.name} (measured by an1078-identify)"
    lines = [
        f"# {args.name}: measured on the board by an1078-identify (self-commissioning, docs/identify.md).",
        f"# The firmware's result: R {r.rs_uohm * 1e-6:.6g} ohm, Ld {r.ld_nh * 1e-6:.6g} mH, "
        f"Lq {r.lq_nh * 1e-6:.6g} mH (per phase),",
        f"# Ke {r.ke_uv_per_rpm * 1e-3:.6g} V/krpm and J {r.j_ng_m2 * 1e-9:.6g} kg m^2 at its build's "
        f"{r.pole_pairs} pole pairs, the inverter's dead time {r.deadtime_ns} ns.",
        "# The rated current and speed are the nameplate's, given to an1078-identify.",
        f"#   tools/tune/tune {args.output}",
        f'name = "{args.name}"',
        f'description = "{desc}"',
        f'board = "{args.board}"',
        "",
        "[motor]",
        f"pole_pairs = {p}",
        f'resistance = "{r.rs_uohm * 1e-6:.6g} ohm"',
        'resistance_kind = "per-phase"',
        f'inductance = "{r.ls_nh * 1e-6:.6g} mH"',
        'inductance_kind = "per-phase"',
        f'back_emf = "{ke:.6g} V/krpm"',
        'back_emf_kind = "peak line-to-line"',
        f'rated_current = "{args.rated_current:g} A"',
        'current_kind = "peak"',
        f'rated_speed = "{args.rated_speed:g} rpm"',
    ]
    if args.peak_current is not None:
        lines.append(f'peak_current = "{args.peak_current:g} A"')
    if r.j_ng_m2 > 0:
        lines.append(f'inertia = "{j:.6g} kg m^2"')
    return "\n".join(lines) + "\n"


def check_args(args: argparse.Namespace) -> None:
    if not 50 <= args.baud <= 4_000_000:
        raise UsageError(f"--baud {args.baud}: outside 50..4000000")
    if '"' in args.description or "\\" in args.description or "\n" in args.description:
        raise UsageError("--description: no quotes, backslashes or line breaks")
    check_output(args.output, "-o", args.force)


def run(args: argparse.Namespace, opener: Callable[[str, int], lnet.Transport] = lnet.open_transport) -> int:
    check_args(args)
    vs = _vars(load_map(args.map))
    names = mc_names.read()
    link = lnet.Link(opener(args.port, args.baud), args.reply_timeout)
    try:
        t = x2c.Target(link)
        t.device_info()
        if not args.no_run:
            run_identification(t, vs, names, args.timeout)
        r = read_result(t, vs)
        fault = _read(t, vs["motor.fault"])
        judge(r, names.state(_read(t, vs["motor.state"])), fault, names.fault(fault))
        if r.status != STATUS_DONE:
            if r.status == STATUS_FAILED:
                why = names.id_error(r.error)
                if why == "FAULT":
                    why += f", {names.fault(_read(t, vs['motor.fault']))}"
                raise lnet.LNetError(f"the identification failed: {why} (firmware/mc_id.h MC_ID_ERROR_LIST); "
                                     f"{args.output} not written")
            raise lnet.LNetError(f"no finished identification on the target (status {r.status}): "
                                 f"{args.output} not written")
        text = describe(r, args)
    finally:
        link.close()
    with replacing(args.output) as tmp, open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    p = args.pole_pairs or r.pole_pairs
    print(f"identify: R {r.rs_uohm * 1e-6:.4g} ohm, L {r.ls_nh * 1e-6:.4g} mH (Ld {r.ld_nh * 1e-6:.4g}, "
          f"Lq {r.lq_nh * 1e-6:.4g}), Ke {r.ke_uv_per_rpm * 1e-3 * p / r.pole_pairs:.4g} V/krpm, "
          f"J {r.j_ng_m2 * 1e-9 * (p / r.pole_pairs) ** 2:.3g} kg m^2, dead time {r.deadtime_ns} ns "
          f"-> {args.output}")
    return 0


def _fail(msg: str, code: int = EXIT_FAIL) -> int:
    print(f"identify: {' '.join(msg.split())}", file=sys.stderr)
    return code


def main(argv: list[str] | None = None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        return run(args)
    except UsageError as e:
        return _fail(str(e), EXIT_USAGE)
    except (lnet.LNetError, MapError, mc_names.McNamesError) as e:
        return _fail(str(e))
    except OSError as e:
        return _fail(f"cannot write: {e.strerror or e}" + (f" ({e.filename})" if e.filename else ""))
    except KeyboardInterrupt:
        return _fail("interrupted", EXIT_INTERRUPTED)
    except Exception as e:  # never a traceback
        return _fail(f"internal error, {type(e).__name__}: {' '.join(str(e).split())}")


if __name__ == "__main__":
    sys.exit(main())
