"""Command line: tools/tune/tune <description.toml> | --check <profile.h>."""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

from . import cheader, derive, describe, emit
from .derive import Infeasible
from .units import InputError

USAGE = """\
tools/tune/tune [options] <motor.toml>      write firmware/motors/motor_<name>.h
tools/tune/tune --check <profile.h> [--board B]   print a profile back in engineering units"""


def _fail(prefix, msg, code):
    print(f"tune: {prefix}{msg}", file=sys.stderr)
    return code


def compile_check(header, board):
    """gcc -fsyntax-only of firmware/mc.c with this profile: the core's own
    compile-time checks. Returns None when it passes (or no gcc), else the
    first error line."""
    cc = shutil.which(os.environ.get("CC", "gcc")) or shutil.which("cc")
    if cc is None:
        return None
    repo = cheader.REPO
    cmd = [cc, "-std=c99", "-fsyntax-only", "-Wall", "-Wextra", "-Werror", "-Wconversion", "-Wsign-conversion",
           "-Wshadow", f"-I{repo}/firmware", f"-I{repo}/foc", f"-I{repo}/smc_estimator",
           f"-DMC_BOARD_{board.upper()}", f'-DMC_MOTOR_HEADER="{os.path.abspath(header)}"',
           os.path.join(repo, "firmware", "mc.c")]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode == 0:
        return None
    errs = [ln for ln in p.stderr.splitlines() if "error" in ln]
    return (errs[0] if errs else p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "compile failed")


def clang_format(text):
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


def generate(path, out_dir=None, out=None, name=None, compile_=True, quiet=False):
    """Returns (exit code, header path or None)."""
    try:
        d = describe.load(path)
        if name is not None:
            d.name = name
        t = derive.derive(d)
    except (InputError, Infeasible) as e:
        return _fail(f"{path}: ", str(e), 2 if isinstance(e, InputError) else 1), None
    target = out or os.path.join(out_dir or os.path.join(cheader.FIRMWARE, "motors"), f"motor_{d.name}.h")
    target_dir = os.path.dirname(os.path.abspath(target))
    if os.path.basename(target) in ("motor_hurst.h", "motor_hurst300.h", "motor_hispeed.h") and \
            os.path.abspath(target_dir) == os.path.join(cheader.FIRMWARE, "motors"):
        return _fail(f"{path}: ", f"name: motor_{d.name}.h is a hand-tuned profile; choose another name", 2), None
    rel_src = os.path.relpath(os.path.abspath(path), cheader.REPO)
    d.source = rel_src if not rel_src.startswith("..") else path
    text = clang_format(emit.render(d, t, f"tools/tune/tune {d.source}"))
    os.makedirs(target_dir, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".motor_{d.name}.", suffix=".h", dir=target_dir)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        core = cheader.derive_core(cheader.profile_env(tmp, d.board))
        if core.failures:
            p, m = core.failures[0]
            return _fail(f"{path}: ", f"{p}: the core would reject the generated value: {m}", 1), None
        if compile_:
            err = compile_check(tmp, d.board)
            if err is not None:
                return _fail(f"{path}: ", f"firmware/mc.c does not compile with the generated profile: {err}", 1), None
        os.replace(tmp, target)
        tmp = None
    finally:
        if tmp is not None and os.path.exists(tmp):
            os.unlink(tmp)
    if not quiet:
        for w in t.warnings:
            print(f"tune: note: {w}", file=sys.stderr)
        print(f"tune: wrote {os.path.relpath(target)} ({d.desc}, board {d.board})")
        print(f"   nominal {t['MOTOR_SPEED_NOMINAL_RPM']:.0f} rpm (bus limit {t.n_bus:.0f} rpm), top "
              f"{t['MOTOR_SPEED_FW_MAX_RPM']:.0f} rpm, min {t['MOTOR_SPEED_MIN_RPM']:.0f} rpm, Iq max "
              f"{t['MOTOR_CURRENT_MAX_A']:.3g} A, trip {t['MOTOR_OVERCURRENT_A']:.3g} A, FW Id at top "
              f"{t.fw_table[-1]:.3f} A")
        print(f"   build and run: make sim MOTOR={d.name} BOARD={d.board}")
    return 0, target


def check(profile, board=None):
    if not os.path.exists(profile):
        return _fail("", f"{profile}: no such file", 2)
    if board is None:
        raw, _ = cheader.read_defines([profile])
        board = raw.get("MOTOR_TUNE_BOARD", '"mclv"').strip('"')
    try:
        env = cheader.profile_env(profile, board)
        core = cheader.derive_core(env)
    except InputError as e:
        return _fail("", str(e), 2)
    except KeyError as e:
        return _fail(f"{profile}: ", f"{e.args[0]}: missing (the core needs it)", 2)
    name = env.get("MOTOR_NAME") if env.has("MOTOR_NAME") else os.path.basename(profile)
    print(cheader.format_table(core, f"{profile}: {name} on board {board} (values as the core computes them)"))
    return 1 if core.failures else 0


def main(argv=None):
    ap = argparse.ArgumentParser(prog="tools/tune/tune", usage=USAGE,
                                 description="Motor profile calculator (AN1078 sensorless FOC).")
    ap.add_argument("description", nargs="?", help="motor description (TOML)")
    ap.add_argument("--check", metavar="PROFILE", help="print a profile header back in engineering units")
    ap.add_argument("--board", help="with --check: the board (default: the one the profile names, else mclv)")
    ap.add_argument("-o", "--output", help="header to write (default firmware/motors/motor_<name>.h)")
    ap.add_argument("--name", help="profile name (overrides the description's)")
    ap.add_argument("--no-compile", action="store_true", help="skip the gcc -fsyntax-only check of firmware/mc.c")
    a = ap.parse_args(argv)
    if a.check:
        return check(a.check, a.board)
    if not a.description:
        ap.print_usage(sys.stderr)
        return 2
    code, _ = generate(a.description, out=a.output, name=a.name, compile_=not a.no_compile)
    return code


if __name__ == "__main__":
    sys.exit(main())
