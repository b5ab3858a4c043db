"""Command line: tools/tune/tune <description.toml> | --check <profile.h>.

Every problem ends in exactly one line on stderr, "tune: <file>: <field>: <why>",
and a non-zero exit: 2 for bad input (InputError), 1 for a request the board
cannot meet or a profile the core would reject, 3 for a fault of the tool
itself (caught by main, still one line: never a traceback).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from typing import NoReturn, Optional

from . import cheader, derive, describe, emit, safeio
from .derive import Infeasible
from .units import InputError, one_line

USAGE = """\
tools/tune/tune [options] <motor.toml>      write firmware/motors/motor_<name>.h
tools/tune/tune --check <profile.h> [--board B]   print a profile back in engineering units"""

HAND_TUNED = ("motor_hurst.h", "motor_hurst300.h", "motor_hispeed.h")


def _fail(prefix: str, msg: str, code: int) -> int:
    print("tune: " + one_line(f"{prefix}{msg}"), file=sys.stderr)
    return code


def find_cc() -> Optional[str]:
    """$CC, else gcc, else cc; None when none is installed."""
    return shutil.which(os.environ.get("CC", "gcc")) or shutil.which("cc")


# The name the compile check gives its copy of the profile: MC_MOTOR_HEADER names it in a
# string literal, which gcc's #include takes as it is (no escapes: a path with '"', a
# backslash or a newline cannot be written there), so the profile is copied under this name.
CC_PROFILE = "tune_check_profile.h"


def compile_check(header: str, board: str) -> Optional[str]:
    """gcc -fsyntax-only of firmware/mc.c with this profile: the core's own
    compile-time checks. Returns None when it passes (or no gcc), else the
    first error line (the copy's path shown as the profile's)."""
    cc = find_cc()
    if cc is None:
        return None
    repo = cheader.REPO
    with tempfile.TemporaryDirectory(prefix="tune_cc_") as tmp:
        copy = os.path.join(tmp, CC_PROFILE)
        try:
            shutil.copyfile(header, copy)
        except OSError as e:
            raise InputError(cheader.label(header), f"cannot copy it for the compile check: {e.strerror}") from None
        cmd = [cc, "-std=c99", "-fsyntax-only", "-Wall", "-Wextra", "-Werror", "-Wconversion", "-Wsign-conversion",
               "-Wshadow", f"-I{repo}/firmware", f"-I{repo}/foc", f"-I{repo}/smc_estimator", "-iquote", tmp,
               f"-DMC_BOARD_{board.upper()}", f'-DMC_MOTOR_HEADER="{CC_PROFILE}"',
               os.path.join(repo, "firmware", "mc.c")]
        p = subprocess.run(cmd, capture_output=True, text=True, errors="replace")
    if p.returncode == 0:
        return None
    errs = [ln for ln in p.stderr.splitlines() if "error" in ln]
    line = errs[0] if errs else p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "compile failed"
    return line.replace(copy, cheader.label(header))


def clang_format(text: str) -> str:
    """The repo's clang-format style (make lint checks firmware/motors/*.h), when installed."""
    exe = shutil.which("clang-format")
    if exe is None:
        return text
    for _ in range(4):  # clang-format is not always idempotent on macro bodies: run to a fixed point
        p = subprocess.run([exe, f"--assume-filename={cheader.FIRMWARE}/motors/motor_x.h"], input=text,
                           capture_output=True, text=True)
        if p.returncode != 0 or not p.stdout or p.stdout == text:
            break
        text = p.stdout
    return text


def _target(name: str, out: Optional[str]) -> safeio.Output:
    """Where the header goes: -o as given (anywhere the user names), else
    firmware/motors/motor_<name>.h (name checked: it cannot leave that folder)."""
    if out is not None:
        return safeio.Output(out, "-o")
    motors = os.path.join(cheader.FIRMWARE, "motors")
    target = os.path.join(motors, f"motor_{name}.h")
    if os.path.basename(target) in HAND_TUNED:
        raise InputError("name", f"motor_{name}.h is a hand-tuned profile; choose another name")
    return safeio.Output(target, "name", root=cheader.REPO)


def generate(path: str, out: Optional[str] = None, name: Optional[str] = None, compile_: bool = True,
             quiet: bool = False) -> tuple[int, Optional[str]]:
    """Returns (exit code, header path or None)."""
    try:
        d = describe.load(path)
        if name is not None:
            d.name = describe.check_name(name, "--name")
        t = derive.derive(d)
        dest = _target(d.name, out)
    except (InputError, Infeasible) as e:
        return _fail(f"{path}: ", str(e), 2 if isinstance(e, InputError) else 1), None
    rel_src = os.path.relpath(os.path.abspath(path), cheader.REPO)
    d.source = rel_src if not rel_src.startswith("..") else path
    text = clang_format(emit.render(d, t, f"tools/tune/tune {d.source}"))
    tmp: Optional[str] = None
    try:
        tmp = dest.write_temp(text)
        core = cheader.derive_core(cheader.profile_env(tmp, d.board))
        if core.failures:
            p, m = core.failures[0]
            return _fail(f"{path}: ", f"{p}: the core would reject the generated value: {m}", 1), None
        if compile_:
            err = compile_check(tmp, d.board)
            if err is not None:
                return _fail(f"{path}: ", f"firmware/mc.c does not compile with the generated profile: {err}", 1), None
        dest.commit(tmp)
        tmp = None
    except InputError as e:
        return _fail(f"{path}: ", str(e), 2), None
    finally:
        dest.discard(tmp)
    target = dest.path
    if not quiet:
        for w in t.warnings + t.limited:
            print("tune: note: " + one_line(w), file=sys.stderr)
        # the path as the user gave it, escaped: a newline or a byte that is not UTF-8 in a
        # file name must neither reach the terminal raw nor fail the print after the write
        print(f"tune: wrote {one_line(os.path.relpath(target), 4096)} ({d.desc}, board {d.board})")
        print(f"   nominal {t['MOTOR_SPEED_NOMINAL_RPM']:.0f} rpm (bus limit {t.n_bus:.0f} rpm), top "
              f"{t['MOTOR_SPEED_FW_MAX_RPM']:.0f} rpm, min {t['MOTOR_SPEED_MIN_RPM']:.0f} rpm, Iq max "
              f"{t['MOTOR_CURRENT_MAX_A']:.3g} A, trip {t['MOTOR_OVERCURRENT_A']:.3g} A, FW Id at top "
              f"{t.fw_table[-1]:.3f} A")
        print(f"   build and run: make sim MOTOR={d.name} BOARD={d.board}")
    return 0, target


def check_profile(profile: str, board: Optional[str] = None) -> tuple[cheader.Derived, str, str]:
    """The core's values for a profile header: (derived, profile name, board). InputError
    for anything that keeps it from being computed."""
    if board is None:
        own = cheader.read_headers([profile], profile=profile)
        board = "mclv"
        if "MOTOR_TUNE_BOARD" in own.raw:
            v = cheader.Env(own).get("MOTOR_TUNE_BOARD")
            if not isinstance(v, str):
                raise InputError("MOTOR_TUNE_BOARD", "must be a string naming the board")
            board = v
    cheader.board_name_ok(board)
    env = cheader.profile_env(profile, board)
    core = cheader.derive_core(env)
    name = env.get("MOTOR_NAME") if env.has("MOTOR_NAME") else os.path.basename(profile)
    return core, one_line(str(name), 100), board


def check(profile: str, board: Optional[str] = None, compile_: bool = True) -> int:
    """The table in engineering units, then the authority: the core's own
    compile-time checks (compile_check), which the table's replay may not
    cover in full."""
    try:
        core, name, board = check_profile(profile, board)
    except InputError as e:
        msg = str(e)
        label = cheader.label(profile)
        return _fail("" if msg.startswith(label) else f"{profile}: ", msg, 2)
    title = f"{one_line(profile)}: {name} on board {board} (values as the core computes them)"
    print(cheader.format_table(core, title))
    if core.failures:
        p, m = core.failures[0]
        more = f" (and {len(core.failures) - 1} more, listed above)" if len(core.failures) > 1 else ""
        return _fail(f"{profile}: ", f"{p}: {m}{more}", 1)
    if compile_:
        if find_cc() is None:
            print("tune: note: no C compiler found: the core's compile-time checks were not run",
                  file=sys.stderr)
            return 0
        err = compile_check(profile, board)
        if err is not None:
            return _fail(f"{profile}: ", f"firmware/mc.c does not compile with this profile: {err}", 1)
    return 0


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        """A usage error in one line too (argparse prints the usage block first)."""
        _fail("", f"{message} (usage: tools/tune/tune --help)", 2)
        raise SystemExit(2)


def _main(argv: Optional[list[str]]) -> int:
    ap = _Parser(prog="tools/tune/tune", usage=USAGE,
                 description="Motor profile calculator (AN1078 sensorless FOC).")
    ap.add_argument("description", nargs="?", help="motor description (TOML)")
    ap.add_argument("--check", metavar="PROFILE", help="print a profile header back in engineering units")
    ap.add_argument("--board", help="with --check: the board (default: the one the profile names, else mclv)")
    ap.add_argument("-o", "--output", help="header to write (default firmware/motors/motor_<name>.h)")
    ap.add_argument("--name", help="profile name (overrides the description's)")
    ap.add_argument("--no-compile", action="store_true",
                    help="skip the compile check of firmware/mc.c with the profile (the core's own checks)")
    a = ap.parse_args(argv)
    if a.check is not None:
        # --check reads a profile and writes nothing: a description, -o or --name would be
        # ignored, so the user would not get what they asked for
        for given, what in ((a.description, "a description"), (a.output, "-o"), (a.name, "--name")):
            if given is not None:
                return _fail("", f"--check: {what} does not go with --check (it reads a profile and writes "
                                 f"nothing; usage: tools/tune/tune --help)", 2)
        return check(a.check, a.board, compile_=not a.no_compile)
    if a.board is not None:
        return _fail("", "--board: goes with --check only (a description names its board; usage: "
                         "tools/tune/tune --help)", 2)
    if not a.description:
        return _fail("", "no description given (usage: tools/tune/tune --help)", 2)
    code, _ = generate(a.description, out=a.output, name=a.name, compile_=not a.no_compile)
    return code


def main(argv: Optional[list[str]] = None) -> int:
    """The command; whatever goes wrong ends in one line on stderr, never a traceback."""
    try:
        return _main(argv)
    except KeyboardInterrupt:
        return _fail("", "interrupted", 130)
    except (InputError, Infeasible) as e:  # a path that forgot to catch its own
        return _fail("", str(e), 2 if isinstance(e, InputError) else 1)
    except BrokenPipeError:
        return 1
    except Exception as e:  # noqa: BLE001 - the promise is one line, even for a bug of the tool
        return _fail("", f"internal error ({type(e).__name__}: {e}); please report it with the input", 3)


if __name__ == "__main__":
    sys.exit(main())
