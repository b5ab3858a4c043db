# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Command line: tools/tune/tune <description.toml> | --check <profile.h>.

Every problem ends in exactly one line on stderr, "tune: <file>: <field>: <why>",
and a non-zero exit: 2 for bad input (InputError, no C compiler), 1 for a
request the board cannot meet or a profile the core rejects, 3 for a fault of
the tool itself (caught by main, still one line: never a traceback).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Callable
from typing import NoReturn

from . import describe, probe, safeio
from .derive import Infeasible
from .generate import build
from .probe import NoCompiler
from .units import InputError, one_line

USAGE = """\
tools/tune/tune [options] <motor.toml>      write firmware/motors/motor_<name>.h
tools/tune/tune --no-tuning --name N <motor.toml>   the profile without the description's [tuning]
tools/tune/tune --check <profile.h> [--board B]   print a profile back in engineering units"""

MAX_HEADER_BYTES = 1 << 20  # a profile --check reads; the shipped ones are 3..25 kB
EXIT_INPUT, EXIT_REFUSED, EXIT_TOOL = 2, 1, 3


def _fail(prefix: str, msg: str, code: int) -> int:
    print("tune: " + one_line(f"{prefix}{msg}"), file=sys.stderr)
    return code


def _target(name: str, out: str | None) -> safeio.Output:
    """Where the header goes: -o as given (anywhere the user names), else
    firmware/motors/motor_<name>.h (name checked: it cannot leave that folder)."""
    if out is not None:
        return safeio.Output(out, "-o")
    target = os.path.join(probe.FIRMWARE, "motors", f"motor_{name}.h")
    return safeio.Output(target, "name", root=str(probe.REPO))


def generate(path: str, out: str | None = None, name: str | None = None, compile_: bool = True,
             quiet: bool = False, tuning: bool = True) -> tuple[int, str | None]:
    """Returns (exit code, header path or None). tuning=False (--no-tuning): without the
    description's [tuning], the profile the tool derives on its own."""
    try:
        d = describe.load(path)
        if not tuning and d.tuning and name is None and out is None:
            raise InputError("--no-tuning", f"give --name or -o: motor_{d.name}.h is the profile with the "
                                            f"description's [tuning]")
        cmd = ["tools/tune/tune"] + ([] if tuning else ["--no-tuning"])
        if name is not None:
            d.name = describe.check_name(name, "--name")
            cmd += ["--name", d.name]
        rel_src = os.path.relpath(os.path.abspath(path), probe.REPO)
        d.source = rel_src if not rel_src.startswith("..") else path
        shown = f"motor_{d.name}.h (generated)"
        g = build(d, " ".join(cmd + [d.source]), shown, tuning)
        dest = _target(d.name, out)
        if compile_:
            err = probe.compile_core(g.text, g.profile.build, shown)
            if err is not None:
                return _fail(f"{path}: ",
                             f"the core (firmware/mc*.c) does not compile with the generated profile: {err}",
                             EXIT_REFUSED), None
    except (InputError, Infeasible) as e:
        return _fail(f"{path}: ", str(e), EXIT_INPUT if isinstance(e, InputError) else EXIT_REFUSED), None
    tmp: str | None = None
    try:
        tmp = dest.write_temp(g.text)
        dest.commit(tmp)
        tmp = None
    except InputError as e:
        return _fail(f"{path}: ", str(e), EXIT_INPUT), None
    finally:
        dest.discard(tmp)
    t = g.tuning
    if not quiet:
        for w in t.warnings + t.limited:
            print("tune: note: " + one_line(w), file=sys.stderr)
        # the path as the user gave it, escaped: a newline or a byte that is not UTF-8 in a
        # file name must neither reach the terminal raw nor fail the print after the write
        print(f"tune: wrote {one_line(os.path.relpath(dest.path), 4096)} ({d.desc}, board {d.board})")
        print(f"   nominal {t['MOTOR_SPEED_NOMINAL_RPM']:.0f} rpm (bus limit {t.n_bus:.0f} rpm), top "
              f"{t['MOTOR_SPEED_FW_MAX_RPM']:.0f} rpm, min {t['MOTOR_SPEED_MIN_RPM']:.0f} rpm, Iq max "
              f"{t['MOTOR_CURRENT_MAX_A']:.3g} A, trip {t['MOTOR_OVERCURRENT_A']:.3g} A, FW Id at top "
              f"{t.fw_table[-1]:.3f} A")
        print(f"   build and run: make sim MOTOR={d.name} BOARD={d.board}")
    return 0, dest.path


def format_table(rows: list[probe.Row], title: str) -> str:
    out = [title, f"{'quantity':34s} {'value':>12s} {'unit':10s} {'Q15/int':>10s} {'decoded':>12s}  note"]
    for r in rows:
        qs = f"{r.q:10d}" if r.q is not None else f"{'':10s}"
        ds = f"{r.decoded:12.6g}" if r.decoded is not None else f"{'':12s}"
        out.append(f"{r.name:34s} {r.eng:12.6g} {r.unit:10s} {qs} {ds}  {r.note}".rstrip())
    return "\n".join(out)


# UserParms.h settings that guard the board, the motor or the start (a profile may set them,
# --check says so): what each one guards.
PROTECTIONS = {
    "MC_SENSOR_CHECK": "the current-sensor check (0: its verdict is ignored)",
    "MC_OVERCURRENT_A": "the overcurrent trip",
    "MC_OFFSET_MAX_A": "the current offsets calibration accepts (the trip's reach)",
    "MC_VBUS_OVERVOLTAGE_V": "the overvoltage trip",
    "MC_VBUS_UNDERVOLTAGE_V": "the undervoltage trip",
    "MC_VBUS_REGEN_V": "the bus level braking is limited from",
    "MC_VBUS_REGEN_BAND_V": "the band over which braking falls to none",
    "MC_STALL_TIME_S": "the stall checks' time",
    "MC_STALL_SPEED_MIN_RPM": "the stall check's lowest speed",
    "MC_STALL_BEMF_LOW_FRACTION": "the stall check's back-EMF floor (0: off)",
    "MC_STALL_BEMF_HIGH_FRACTION": "the stall check's back-EMF ceiling",
    "MC_STALL_SPEED_ERROR_RPM": "the tracking stall check",
    "MC_STALL_TRACK_TIME_S": "the tracking stall check's time",
    "MC_SWING_FLIPS": "the speed loop's limit-cycle check (reversals)",
    "MC_SWING_GAP_S": "the speed loop's limit-cycle check (gap)",
    "MC_SENSOR_TIME_S": "the current-sensor check's time",
    "MC_START_RETRIES": "the retries a locked rotor takes",
    "MC_RETRY_COAST_S": "the coast between retries",
    "MC_HANDOFF_SPEED_TOL": "the hand-off's agreement",
    "MC_DEADTIME_MEASURE": "the dead-time measurement at the lock (0: PWM_DEADTIME_NS trusted)",
    "MC_DEADTIME_COMP": "the dead-time compensation (0: off)",
    "MC_ID_CURRENT_A": "the identification's current",
}


def settings_changed(macros: dict[str, str]) -> list[str]:
    """A line for each UserParms.h setting (MC_*) the profile sets in its place, the protections
    named as such: a profile that moves one is listed, never passed without a word."""
    out = []
    for name in sorted(n for n in macros if n.startswith("MC_")):
        value = one_line(macros[name].strip(), 40)
        if name in PROTECTIONS:
            out.append(f"PROTECTION  {name} {value}: set by the profile, not UserParms.h: {PROTECTIONS[name]}")
        else:
            out.append(f"SETTING     {name} {value}: set by the profile, not UserParms.h")
    return out


def unusual(f: Callable[[str], float]) -> list[str]:
    """A line for each value the core accepts but a slip makes likely (f: the probe's facts):
    legal, so --check passes, but said, with the reason."""
    out = []
    e_ph = f("MOTOR_KE_VPK_LL_PER_KRPM") / math.sqrt(3.0) / 1000.0  # V phase peak per rpm
    v_lim = f("MC_VOLTAGE_LIMIT_FRACTION") * f("MC_VOLTAGE_FULLSCALE_V")
    share = e_ph * f("MOTOR_SPEED_NOMINAL_RPM") / v_lim
    if share < 0.5:
        out.append(f"WARNING     MOTOR_KE_VPK_LL_PER_KRPM: the back-EMF at the nominal speed is {share:.0%} of "
                   f"the voltage the core applies (field weakening starts there): Ke given as rms or per "
                   f"phase (x{math.sqrt(6):.2f} or x{math.sqrt(3):.2f} low)?")
    v_dt = 4.0 / math.pi * 2.0 / 3.0 * f("PWM_DEADTIME_NS") * 1e-9 * f("PWM_FREQUENCY_HZ") * \
        f("BOARD_VBUS_NOMINAL_V")
    e_min = e_ph * f("MOTOR_SPEED_MIN_RPM")
    if e_min < 3.0 * v_dt:
        out.append(f"WARNING     MOTOR_SPEED_MIN_RPM: its back-EMF {e_min:.2f} V is {e_min / v_dt:.1f} x the dead "
                   f"time's voltage error {v_dt:.2f} V (the core refuses 1 x; tools/tune derives 3 x)")
    if f("MOTOR_RAMP_TIME_S") < 0.25:
        out.append(f"WARNING     MOTOR_RAMP_TIME_S: {f('MOTOR_RAMP_TIME_S'):g} s leaves the estimator little "
                   "to converge and the lock's swing no time to die before the hand-off (tools/tune derives "
                   "at least 1 s)")
    if f("MC_VBUS_OVERVOLTAGE_V") > 1.5 * f("BOARD_VBUS_NOMINAL_V"):
        out.append(f"WARNING     MC_VBUS_OVERVOLTAGE_V: {f('MC_VBUS_OVERVOLTAGE_V'):g} V trips at "
                   f"{f('MC_VBUS_OVERVOLTAGE_V') / f('BOARD_VBUS_NOMINAL_V'):.2f} x the "
                   f"{f('BOARD_VBUS_NOMINAL_V'):g} V bus: a regenerating motor pumps it that far first")
    if f("PWM_ADC_TRIGGER_TCY") < f("MC_DT_COUNTS"):
        out.append(f"WARNING     PWM_ADC_TRIGGER_TCY: the sample {f('PWM_ADC_TRIGGER_TCY'):g} Tcy after the "
                   f"midpoint, less than a dead time ({f('MC_DT_COUNTS'):g} Tcy): the shunt window then takes "
                   "the settling from the duty (AN1078: 80 Tcy)")
    return out


def check(profile: str, board: str | None = None, compile_: bool = True) -> int:
    """The table in engineering units as the core computes it (the probe), the checks of
    mc_derived.h and smc.h that fail, then the core's own compile (firmware/mc*.c)."""
    shown = probe.label(profile)
    try:
        text = safeio.read_utf8(profile, shown, MAX_HEADER_BYTES)
        if board is None:
            board = probe.tune_board(text, shown) or probe.DEFAULT_BOARD
        probe.board_header(board)
        prof = probe.profile(text, board, shown)
    except InputError as e:
        msg = str(e)
        return _fail("" if msg.startswith(shown) else f"{profile}: ", msg, EXIT_INPUT)
    name = prof.out.texts.get("MOTOR_NAME") or prof.macros.string("MOTOR_NAME") or os.path.basename(profile)
    title = f"{one_line(profile)}: {one_line(name, 100)} on board {board} (values as the core computes them)"
    if prof.refused:
        print(f"{title}\n")
        for r in prof.refused:
            print(f"CHECK FAILED  {r.line()}")
        first = prof.refused[0]
        more = f" (and {len(prof.refused) - 1} more, listed above)" if len(prof.refused) > 1 else ""
        return _fail(f"{profile}: ", f"{first.param}: {first.why} ({first.where}){more}", EXIT_REFUSED)
    print(format_table(prof.out.rows, title))
    for line in settings_changed(prof.macros.macros) + unusual(prof.out.fact):
        print(line)
    if compile_:
        err = probe.compile_core(text, prof.build, shown)
        if err is not None:
            return _fail(f"{profile}: ", f"the core (firmware/mc*.c) does not compile with this profile: {err}",
                         EXIT_REFUSED)
        print("every check of mc_derived.h / smc.h / the core passes")
    else:
        print("every check of mc_derived.h / smc.h passes (the core not compiled: --no-compile)")
    return 0


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        """A usage error in one line too (argparse prints the usage block first)."""
        _fail("", f"{message} (usage: tools/tune/tune --help)", EXIT_INPUT)
        raise SystemExit(EXIT_INPUT)


def _main(argv: list[str] | None) -> int:
    ap = _Parser(prog="tools/tune/tune", usage=USAGE,
                 description="Motor profile calculator (AN1078 sensorless FOC).")
    ap.add_argument("description", nargs="?", help="motor description (TOML)")
    ap.add_argument("--check", metavar="PROFILE", help="print a profile header back in engineering units")
    ap.add_argument("--board", help="with --check: the board (default: the one the profile names, else mclv)")
    ap.add_argument("-o", "--output", help="header to write (default firmware/motors/motor_<name>.h)")
    ap.add_argument("--name", help="profile name (overrides the description's)")
    ap.add_argument("--no-tuning", action="store_true",
                    help="leave the description's [tuning] out: the profile the tool derives on its own "
                         "(with --name or -o when the description has a [tuning])")
    ap.add_argument("--no-compile", action="store_true",
                    help="skip the compile of the core (firmware/mc*.c) with the profile (the core's checks in "
                         "mc_derived.h still judge it, through the probe)")
    a = ap.parse_args(argv)
    if a.check is not None:
        # --check reads a profile and writes nothing: a description, -o or --name would be
        # ignored, so the user would not get what they asked for
        for given, what in ((a.description, "a description"), (a.output, "-o"), (a.name, "--name"),
                            (a.no_tuning or None, "--no-tuning")):
            if given is not None:
                return _fail("", f"--check: {what} does not go with --check (it reads a profile and writes "
                                 f"nothing; usage: tools/tune/tune --help)", EXIT_INPUT)
        return check(a.check, a.board, compile_=not a.no_compile)
    if a.board is not None:
        return _fail("", "--board: goes with --check only (a description names its board; usage: "
                         "tools/tune/tune --help)", EXIT_INPUT)
    if not a.description:
        return _fail("", "no description given (usage: tools/tune/tune --help)", EXIT_INPUT)
    code, _ = generate(a.description, out=a.output, name=a.name, compile_=not a.no_compile, tuning=not a.no_tuning)
    return code


def main(argv: list[str] | None = None) -> int:
    """The command; whatever goes wrong ends in one line on stderr, never a traceback."""
    try:
        return _main(argv)
    except KeyboardInterrupt:
        return _fail("", "interrupted", 130)
    except NoCompiler as e:
        return _fail("", str(e), EXIT_INPUT)
    except (InputError, Infeasible) as e:  # a path that forgot to catch its own
        return _fail("", str(e), EXIT_INPUT if isinstance(e, InputError) else EXIT_REFUSED)
    except BrokenPipeError:
        return 1
    except Exception as e:
        return _fail("", f"internal error ({type(e).__name__}: {e}); please report it with the input", EXIT_TOOL)


if __name__ == "__main__":
    sys.exit(main())
