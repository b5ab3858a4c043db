# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Hostile inputs to tools/tune, each with the answer it must get.

The review of tools/tune (docs/tune.md, "Input safety") found that --check ran
code from the header it read, that -o overwrote whatever it was given, that a
name or a description could break out into C, and that bad input gave
tracebacks or, worse, useless profiles. Every input of that review and more is
listed here with what the tool must answer: exactly one line on stderr that
starts with "tune: " and names the field or file, a non-zero exit, no
traceback, nothing written, nothing executed, within a time bound. Each
answer is printed ("measured: hostile ...") so ctest -V shows the list.

Since tools/tune reads headers through the C compiler (motortune/probe.py), a
header is answered as the compiler reads it: what C computes is computed (100
nested parentheses are 2.67), what C refuses is refused naming the profile's
macro, what the core's checks refuse fails the check; and a header that is not
data (code, #include, #pragma, a value that could leave its expression) is
refused before anything is compiled, so nothing from it ever runs.

Everything runs the command (tools/tune/tune) in a subprocess on copies in a
scratch directory: never on firmware/ itself.

Run: .venv/bin/python -m unittest -v test_tune_hostile   (from test/tune; CTest does it)
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import shutil
import stat
import subprocess
import time
import unittest
from collections.abc import Callable

from test_tune_unit import HURST_TOML, scratch, setUpModule  # noqa: F401 - the unit tests' fixture
from tune.motortune import cli, derive, probe, safeio
from tune.motortune.derive import Tuning
from tune.motortune.describe import Description
from tune.motortune.units import InputError

REPO = str(probe.REPO)
TUNE = os.path.join(REPO, "tools", "tune", "tune")
MOTORS = os.path.join(REPO, "firmware", "motors")
TIMEOUT_S = 30.0  # per command; a well-behaved answer takes about a second (it compiles)

# The Hurst description the unit tests use, under its own name and with a
# description (the hostile cases rewrite fields of it).
BASE_TOML = HURST_TOML.replace('name = "hurst_t"\n',
                               'name = "hostile_t"\ndescription = "hostile test motor"\n')


def run_tune(*args: str, umask: int | None = None, env: dict[str, str] | None = None,
             cwd: str | None = None) -> tuple[int, list[str], str, float]:
    """(exit code, stderr lines, stdout, seconds); a hang is a failure, not a wait."""
    def pre() -> None:
        if umask is not None:
            os.umask(umask)
    t0 = time.monotonic()
    try:
        r = subprocess.run([TUNE, *args], capture_output=True, text=True, errors="replace",
                           timeout=TIMEOUT_S, preexec_fn=pre if umask is not None else None,
                           env=None if env is None else {**os.environ, **env}, cwd=cwd)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"tools/tune {' '.join(args)[:80]}: no answer within {TIMEOUT_S:.0f} s") from None
    return r.returncode, r.stderr.strip().splitlines(), r.stdout, time.monotonic() - t0


def replace_define(text: str, name: str, body: str) -> str:
    """The header with `#define name ...` given another body (the line must exist)."""
    new, n = re.subn(rf"^#define {name} .*$", lambda _: f"#define {name} {body}", text, count=1, flags=re.M)
    assert n == 1, name
    return new


def sha(path: str | bytes) -> bytes:
    with open(path, "rb") as f:
        return f.read()


def hurst075_path() -> str:
    """The profile tools/tune gives on its own for the Hurst (no [tuning]): the build tree's
    (TUNE_PROFILES), else written into the scratch folder."""
    built = os.path.join(os.environ.get("TUNE_PROFILES", "/nonexistent"), "motor_hurst075.h")
    if os.path.exists(built):
        return built
    out = os.path.join(scratch(), "motor_hurst075.h")
    r = subprocess.run([TUNE, "--no-tuning", "--no-compile", "--name", "hurst075", "-o", out,
                        os.path.join(REPO, "tools", "tune", "examples", "hurst.toml")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out


def hurst075() -> str:
    with open(hurst075_path(), encoding="utf-8") as f:
        return f.read()


class Hostile(unittest.TestCase):
    def setUp(self) -> None:
        self.dir = scratch()

    def tearDown(self) -> None:
        shutil.rmtree(self.dir, ignore_errors=True)

    def one_line(self, label: str, code: int, lines: list[str], want_code: int | None = None,
                 fragment: str = "") -> None:
        """The contract: non-zero (or want_code), one line "tune: ...", the fragment, no traceback."""
        print(f"measured: hostile {label}: exit {code}: {lines[0] if lines else '(no stderr)'}")
        self.assertEqual(len(lines), 1, f"{label}: stderr must be one line, got {lines[:6]}")
        self.assertTrue(lines[0].startswith("tune: "), f"{label}: {lines[0]}")
        self.assertNotIn("Traceback", lines[0])
        if want_code is None:
            self.assertNotEqual(code, 0, label)
        else:
            self.assertEqual(code, want_code, f"{label}: {lines[0]}")
        self.assertIn(fragment, lines[0], label)

    def write(self, name: str, data: str | bytes) -> str:
        p = os.path.join(self.dir, name)
        with open(p, "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode("utf-8"))
        return p


# ---- defect 1: --check executes the header it reads --------------------------------------

class CheckNeverExecutes(Hostile):
    """--check reads a header as data: nothing of it runs, #if 0 is honoured, the work is bounded."""

    base: str

    @classmethod
    def setUpClass(cls) -> None:
        cls.base = hurst075()

    def payload(self, marker: str) -> str:
        # What the review used: Python that runs a shell command through eval. Every name
        # in it was also #defined (inside #if 0, where the compiler never looks), so the
        # old reader's name lookup let the expression through to eval.
        return (f"[c.__init__.__globals__['system']('touch {marker}') for c in ().__class__.__base__."
                f"__subclasses__() if c.__name__ == '_wrap_close'][0] * 0 + 2.67")

    def disguised(self, marker: str, guard: str) -> str:
        """The payload as MOTOR_RS_OHM inside `guard` (#if 0...), with every identifier of it
        #defined there too, before the real definitions."""
        pay = self.payload(marker)
        idents = sorted(set(re.findall(r"[A-Za-z_]\w*", pay)))
        block = (f"{guard}\n" + "".join(f"#define {i} 0\n" for i in idents)
                 + f"#define MOTOR_RS_OHM {pay}\n#endif\n")
        return self.base.replace("#define MOTOR_HURST075_H\n", "#define MOTOR_HURST075_H\n" + block, 1)

    def test_a_payload_inside_if_0_should_be_skipped_and_never_run(self) -> None:
        marker = os.path.join(self.dir, "PWNED")
        h = self.write("evil.h", self.disguised(marker, "#if 0"))
        # the header is valid C: the compiler skips the block
        cmd = [*probe.find_cc(), "-std=c99", "-fsyntax-only", "-Wall", "-Wextra", "-Werror",
               "-DPWM_FREQUENCY_HZ=20000L", "-x", "c", h]
        r = subprocess.run(cmd, capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        code, lines, out, _ = run_tune("--check", h)
        ran = "CREATED" if os.path.exists(marker) else "absent"
        print(f"measured: hostile payload in #if 0: exit {code}, marker file {ran}")
        self.assertFalse(os.path.exists(marker), "--check ran the header's code")
        self.assertEqual(code, 0, lines)
        self.assertIn("F (AN1078 Eq. 2: 1 - Ts R/L)           0.930469", out)  # the real R, 2.67 ohm, was read

    def test_payloads_in_other_skipped_groups_should_not_run(self) -> None:
        for guard in ("#ifdef NOT_DEFINED_ANYWHERE", "#if defined(MC_BOARD_MCHV)", "#ifndef MOTOR_HURST075_H",
                      "#if 1 - 1", "#if 0 && (1 / 0)"):
            with self.subTest(guard):
                marker = os.path.join(self.dir, "PWNED")
                h = self.write("evil.h", self.disguised(marker, guard))
                code, lines, _, _ = run_tune("--check", h)
                print(f"measured: hostile payload under '{guard}': exit {code}")
                self.assertFalse(os.path.exists(marker))
                self.assertEqual(code, 0, lines)

    def test_a_live_payload_should_be_refused_in_one_line_and_never_run(self) -> None:
        # its lower-case macros (and the values' '.' and quotes) are refused before any compile
        marker = os.path.join(self.dir, "PWNED")
        h = self.write("evil.h", self.disguised(marker, "#if 1"))
        code, lines, _, _ = run_tune("--check", h)
        self.assertFalse(os.path.exists(marker), "--check ran the header's code")
        self.one_line("live payload (#if 1)", code, lines, 2, "upper-case")

    def test_each_non_c_expression_should_be_refused_naming_the_macro(self) -> None:
        marker = os.path.join(self.dir, "PWNED")
        cases = [
            ("Python power 9**9**9 (used to hang)", "9**9**9", "MOTOR_RS_OHM"),
            ("__import__ call", f"__import__('os').system('touch {marker}')", "MOTOR_RS_OHM"),
            ("attribute access", "(1).__class__", "MOTOR_RS_OHM"),
            ("lambda", "(lambda: 2.67)()", "MOTOR_RS_OHM"),
            ("indexing", "[2.67][0]", "MOTOR_RS_OHM"),
            ("string literal", '"2.67"', "MOTOR_RS_OHM"),
            ("function-style call", "pow(2, 3)", "MOTOR_RS_OHM"),
            ("Python conditional", "2.67 if 1 else 0", "MOTOR_RS_OHM"),
            ("Python 'and'", "1 and 2.67", "MOTOR_RS_OHM"),
            ("comma operator", "(1, 2.67)", "MOTOR_RS_OHM"),
            ("a statement", "2.67; }", "MOTOR_RS_OHM"),
            ("undefined name", "NO_SUCH_MACRO * 2", "NO_SUCH_MACRO"),
            ("self-reference (C does not expand it again)", "MOTOR_RS_OHM", "MOTOR_RS_OHM"),
            ("1e999", "1e999", "MOTOR_RS_OHM"),
            ("a 40-digit integer", "1" * 40, "MOTOR_RS_OHM"),
            ("1e300 * 1e300", "1e300 * 1e300", "MOTOR_RS_OHM"),
            ("division by zero", "(2.67 / 0)", "MOTOR_RS_OHM"),
            ("empty body", "", "MOTOR_RS_OHM"),
        ]
        for label, body, fragment in cases:
            with self.subTest(label):
                h = self.write("bad.h", replace_define(self.base, "MOTOR_RS_OHM", body))
                code, lines, _, secs = run_tune("--check", h)
                self.one_line(f"--check MOTOR_RS_OHM {label}", code, lines, 2, fragment)
                self.assertLess(secs, TIMEOUT_S)
                self.assertFalse(os.path.exists(marker))

    def test_c_expressions_should_be_computed_as_the_compiler_computes_them(self) -> None:
        # C, not a refusal: the value the compiler gets, judged by the core's checks
        cases = [
            ("bitwise shift", "(1 << 2)", 1, "MOTOR_SPEED_FW_MAX_RPM"),  # 4 ohm: the top speed is out of reach
            ("100 nested parentheses", "(" * 100 + "2.67" + ")" * 100, 0, ""),
            ("3000 unary minuses", "- " * 3000 + "2.67", 0, ""),
            ("3000 tokens", "+".join(["1"] * 1500), 1, "MOTOR_RS_OHM"),  # 1500 ohm
            ("cast out of int16 range", "(int16_t)40000", 1, "MOTOR_RS_OHM: must be > 0"),  # -25536 ohm
        ]
        for label, body, want, fragment in cases:
            with self.subTest(label):
                h = self.write("c.h", replace_define(self.base, "MOTOR_RS_OHM", body))
                code, lines, _, secs = run_tune("--check", h, "--no-compile")
                if want:
                    self.one_line(f"--check MOTOR_RS_OHM {label}", code, lines, want, fragment)
                else:
                    print(f"measured: hostile MOTOR_RS_OHM {label}: exit {code}, computed by C in {secs:.1f} s")
                    self.assertEqual(code, 0, lines)
                self.assertLess(secs, TIMEOUT_S)

    def test_a_macro_cycle_should_be_refused(self) -> None:
        text = replace_define(self.base, "MOTOR_RS_OHM", "MOTOR_LS_H")
        text = replace_define(text, "MOTOR_LS_H", "(MOTOR_RS_OHM * 1)")
        code, lines, _, _ = run_tune("--check", self.write("cycle.h", text))
        self.one_line("--check macro cycle", code, lines, 2, "undeclared")

    def test_a_fw_table_entry_payload_should_be_refused(self) -> None:
        text = self.base.replace("X(0.000)", "X(__import__('os').getcwd())", 1)
        code, lines, _, _ = run_tune("--check", self.write("fw.h", text))
        self.one_line("--check FW table entry payload", code, lines, 2, "MOTOR_FW_ID_TABLE_A")

    def test_directives_it_does_not_read_should_be_refused(self) -> None:
        # the preprocessor's own answer, at the profile's line (the wording is the compiler's)
        cases = [
            ("#error in a read group", "#error stop here\n", "#error"),
            ("unknown directive", "#frobnicate 1\n", "frobnicate"),
            ("#endif without #if", "#endif\n", "#endif without #if"),
            ("#if without #endif", "#if 1\n", "dir.h:"),
            ("#else twice", "#if 0\n#else\n#else\n#endif\n", "#else"),
            ("#if with a float", "#if 1.5\n#endif\n", "dir.h:"),
            ("#ifdef without a name", "#ifdef\n#endif\n", "dir.h:"),
            ("unterminated comment (it swallows the guard's #endif)", "/* no end\n", "dir.h:"),
            ("conflicting redefinition", "#define MOTOR_POLE_PAIRS 4\n", "MOTOR_POLE_PAIRS"),
            # the build would read the included file's values, --check would not: refused
            ("#include in a profile", '#include "motor_hurst.h"\n', "dir.h:"),
            ("#include of a file that is there", '#include "UserParms.h"\n', "#include"),
            ("a pragma", "#pragma weak puts = system\n", "#pragma"),
            ("a floating constant in #if (the preprocessor refuses it)", "#if 1.5 > 1\n#endif\n", "dir.h:"),
        ]
        for label, insert, fragment in cases:
            with self.subTest(label):
                text = self.base.replace("#endif /* MOTOR_HURST075_H */", insert + "#endif /* MOTOR_HURST075_H */")
                code, lines, _, _ = run_tune("--check", self.write("dir.h", text))
                self.one_line(f"--check {label}", code, lines, 2, fragment)
        code, lines, _, _ = run_tune("--check", self.write("dir.h", self.base + "/* no end\n"))
        self.one_line("--check unterminated comment at the end", code, lines, 2, "comment")
        # inside #if 0 the compiler does not read the #include either
        text = self.base.replace("#endif /* MOTOR_HURST075_H */", '#if 0\n#include "x.h"\n#endif\n'
                                 "#endif /* MOTOR_HURST075_H */")
        code, lines, _, _ = run_tune("--no-compile", "--check", self.write("dir.h", text))
        self.assertEqual(code, 0, lines)


# ---- defect 4 (--check side): tracebacks on bad values --------------------------------------

class CheckBadValues(Hostile):
    base: str

    @classmethod
    def setUpClass(cls) -> None:
        cls.base = hurst075()

    def test_values_the_core_cannot_take_should_be_one_line_naming_them(self) -> None:
        cases = [  # (label, macro, body, exit code, fragment)
            ("pole pairs 0", "MOTOR_POLE_PAIRS", "0", 1, "MOTOR_POLE_PAIRS"),
            ("pole pairs 2.5", "MOTOR_POLE_PAIRS", "2.5", 1, "MOTOR_POLE_PAIRS"),
            ("pole pairs -5", "MOTOR_POLE_PAIRS", "(-5)", 1, "MOTOR_POLE_PAIRS"),
            ("a string for R", "MOTOR_RS_OHM", '"2.67"', 2, "MOTOR_RS_OHM"),
            ("board traversal", "MOTOR_TUNE_BOARD", '"../../../etc/x"', 2, "board"),
        ]
        for label, name, body, want, fragment in cases:
            with self.subTest(label):
                code, lines, _, _ = run_tune("--check", self.write("v.h", replace_define(self.base, name, body)))
                self.one_line(f"--check {label}", code, lines, want, fragment)
        # the PWM is the board's (boards/board.h): a profile that sets it is refused
        for name, body in (("PWM_FREQUENCY_HZ", "0L"), ("PWM_ADC_TRIGGER_TCY", "1e308")):
            with self.subTest(name):
                text = self.base.replace("#endif /* MOTOR_HURST075_H */",
                                         f"#define {name} {body}\n#endif /* MOTOR_HURST075_H */")
                code, lines, _, _ = run_tune("--check", self.write("v.h", text))
                self.one_line(f"--check a profile that sets {name}", code, lines, 2, name)

    def test_values_the_core_rejects_should_fail_the_check_in_one_stderr_line(self) -> None:
        cases = [
            ("observer band 0 (used to divide by zero)", "MOTOR_SMC_LINEAR_BAND_A", "0.0", "MOTOR_SMC_LINEAR_BAND_A"),
            ("speed Ki rounding to 0", "MOTOR_SPEED_KI_A_PER_RPM_S", "1e-9", "rounding to 0"),
            ("speed Kp rounding to 0 (inertia in g cm^2 read as kg m^2)", "MOTOR_SPEED_KP_A_PER_RPM", "2.58e-10",
             "rounding to 0"),
            ("current Ki 0", "MOTOR_CURRENT_KI_V_PER_AS", "0.0", "rounding to 0"),
            ("ramp time 1e300 s", "MOTOR_RAMP_TIME_S", "1e300", "MOTOR_RAMP_TIME_S"),
            ("negative inductance", "MOTOR_LS_H", "(-1.92e-3)", "MOTOR_LS_H"),
        ]
        for label, name, body, fragment in cases:
            with self.subTest(label):
                code, lines, out, _ = run_tune("--check", self.write("v.h", replace_define(self.base, name, body)))
                self.one_line(f"--check {label}", code, lines, 1, fragment)
                self.assertIn("CHECK FAILED", out)
        text = self.base.replace("#define MOTOR_POLE_PAIRS 5", "#define MOTOR_POLE_PAIRS 5\n#define "
                                 "MC_VOLTAGE_LIMIT_FRACTION 2.0")
        code, lines, _, _ = run_tune("--check", self.write("v.h", text))
        self.one_line("--check voltage limit fraction 2 (used to raise ValueError)", code, lines, 1,
                      "MC_VOLTAGE_LIMIT_FRACTION")

    def test_values_beyond_every_range_should_fail_the_check_naming_the_macro(self) -> None:
        # each used to end in "internal error" (OverflowError, ValueError), exit 3; now the
        # compiler's answer: a failed check (listed on stdout), or a constant it cannot compute
        cases = [
            ("open-loop damping 1e305 s (int of inf)", {"MOTOR_OL_DAMP_S": "1e305"}, "MOTOR_OL_DAMP_S"),
            ("estimator floor 90000 rpm on a 100000 rpm scale (Q15 of more than 1)",
             {"MC_ESTIMATOR_MIN_RPM": "90000.0", "MC_SPEED_FULLSCALE_RPM": "100000.0"}, "MC_ESTIMATOR_MIN_RPM"),
        ]
        for label, defines, fragment in cases:
            with self.subTest(label):
                text = self.base
                for name, body in defines.items():
                    if re.search(rf"^#define {name} ", text, flags=re.M):
                        text = replace_define(text, name, body)
                    else:
                        text = text.replace("#endif /* MOTOR_HURST075_H */",
                                            f"#define {name} {body}\n#endif /* MOTOR_HURST075_H */")
                code, lines, out, _ = run_tune("--check", self.write("v.h", text))
                self.one_line(f"--check {label}", code, lines)
                self.assertIn(fragment, lines[0] + out)

    def test_macros_set_to_extremes_should_give_only_the_tools_own_answers(self) -> None:
        # In-process, through the probe: each macro the profile sets, and two UserParms.h
        # settings, at each extreme in turn: a table, a failed check or an InputError, never
        # another exception (--check's exit 3). A sample: each case compiles the core.
        names = ["MOTOR_POLE_PAIRS", "MOTOR_RS_OHM", "MOTOR_LS_H", "MOTOR_SPEED_FULLSCALE_RPM", "MOTOR_LOCK_TIME_S",
                 "MOTOR_RAMP_TIME_S", "MOTOR_SMC_GAIN_V", "MOTOR_CURRENT_KP_V_PER_A", "MC_ESTIMATOR_MIN_RPM",
                 "MC_SPEED_FILTER_HZ"]
        extremes = ["1e305", "-1e305", "1e-305", "0", "(-1)", "32768", "9223372036854775807"]
        crashed, answers = [], {"table": 0, "refused": 0, "input": 0}
        for name in names:
            for v in extremes:
                if re.search(rf"^#define {name} ", self.base, flags=re.M):
                    text = replace_define(self.base, name, v)
                else:
                    text = self.base.replace("#endif /* MOTOR_HURST075_H */",
                                             f"#define {name} {v}\n#endif /* MOTOR_HURST075_H */")
                try:
                    prof = probe.profile(text, "mclv", "x.h")
                    answers["refused" if prof.refused else "table"] += 1
                except InputError:
                    answers["input"] += 1
                except Exception as e:
                    crashed.append(f"{name}={v}: {type(e).__name__}: {e}")
        print(f"measured: hostile {len(names) * len(extremes)} extreme macro values in-process: {answers}, "
              f"{len(crashed)} exceptions")
        self.assertEqual(crashed, [])

    def test_files_that_are_not_headers_should_be_refused(self) -> None:
        d = self.dir
        fifo = os.path.join(d, "fifo.h")
        os.mkfifo(fifo)
        cases = [
            ("a directory", d, "directory"),
            ("a fifo (used to block forever)", fifo, "fifo"),
            ("/dev/null", "/dev/null", "character device"),
            ("a missing file", os.path.join(d, "none.h"), "No such file"),
            ("not UTF-8", self.write("bin.h", b"#define X \xff\xfe\n"), "UTF-8"),
            ("2 MB", self.write("big.h", b"/*" + b" " * (2 << 20) + b"*/"), "too large"),
        ]
        for label, path, fragment in cases:
            with self.subTest(label):
                code, lines, _, _ = run_tune("--check", path)
                self.one_line(f"--check {label}", code, lines, 2, fragment)
        code, lines, _, _ = run_tune("--check", hurst075_path(), "--board", "../x")
        self.one_line("--check --board ../x", code, lines, 2, "board")


# ---- defect 2: -o writes whatever it is given ------------------------------------------------

class OutputIsSafe(Hostile):
    def setUp(self) -> None:
        super().setUp()
        self.toml = self.write("m.toml", BASE_TOML)
        self.hand = os.path.join(self.dir, "motors", "motor_hurst.h")  # a copy: never the real one
        os.makedirs(os.path.dirname(self.hand))
        # a hand-written header: the committed profile without the generator's mark
        with open(os.path.join(MOTORS, "motor_hurst.h"), encoding="utf-8") as f:
            text = f.read().replace("generated by tools/tune", "written by hand")
        with open(self.hand, "w", encoding="utf-8") as f:
            f.write(text)

    def generated(self, name: str = "motor_gen.h") -> str:
        p = os.path.join(self.dir, name)
        code, lines, _, _ = run_tune("--no-compile", "-o", p, self.toml)
        self.assertEqual(code, 0, lines)
        return p

    def test_special_files_should_be_refused(self) -> None:
        fifo = os.path.join(self.dir, "fifo.h")
        os.mkfifo(fifo)
        os.mkdir(os.path.join(self.dir, "adir"))
        for label, target, fragment in (("a fifo", fifo, "fifo"),
                                        ("a directory (used to give a traceback)", os.path.join(self.dir, "adir"),
                                         "directory"),
                                        ("an empty path", "", "-o")):
            with self.subTest(label):
                code, lines, _, _ = run_tune("--no-compile", "-o", target, self.toml)
                self.one_line(f"-o {label}", code, lines, 2, fragment)
        self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))
        self.assertEqual([f for f in os.listdir(self.dir) if f.endswith(".tmp")], [])

    def test_a_device_should_be_refused_before_anything_is_written(self) -> None:
        # In-process, on the check alone: a tool that regressed must not get the chance to
        # replace the machine's /dev/null (the review's tools/tune did, run as root).
        for dev in ("/dev/null", "/dev/zero"):
            with self.subTest(dev):
                with self.assertRaises(InputError) as cm:
                    safeio.Output(dev, "-o")
                print(f"measured: hostile -o {dev}: {cm.exception}")
                self.assertIn("character device", str(cm.exception))
        self.assertTrue(stat.S_ISCHR(os.stat("/dev/null").st_mode))

    def test_a_missing_directory_should_be_refused_not_created(self) -> None:
        target = os.path.join(self.dir, "no", "such", "motor_x.h")
        code, lines, _, _ = run_tune("--no-compile", "-o", target, self.toml)
        self.one_line("-o into a missing directory", code, lines, 2, "-o")
        self.assertFalse(os.path.exists(os.path.join(self.dir, "no")))

    def test_a_hand_written_header_should_never_be_overwritten(self) -> None:
        before = sha(self.hand)
        code, lines, _, _ = run_tune("--no-compile", "-o", self.hand, self.toml)
        self.one_line("-o a hand-written header (a copy of motor_hurst.h)", code, lines, 2, "not generated")
        self.assertEqual(sha(self.hand), before)

    def test_a_symlinked_directory_the_user_names_should_be_followed_to_its_real_folder(self) -> None:
        # -o is "anywhere the user names": a folder that is a link (macOS /tmp) is resolved
        # once and the write happens in the real folder; what is there is judged as always
        link = os.path.join(self.dir, "link")
        os.symlink(os.path.dirname(self.hand), link)
        before = sha(self.hand)
        code, lines, _, _ = run_tune("--no-compile", "-o", os.path.join(link, "motor_hurst.h"), self.toml)
        self.one_line("-o through a symlinked folder onto motor_hurst.h (a copy)", code, lines, 2, "not generated")
        self.assertEqual(sha(self.hand), before)
        gen = self.generated(os.path.join("motors", "motor_gen.h"))
        os.chmod(gen, 0o644)
        with open(gen, "a") as f:
            f.write("/* stale */\n")
        code, lines, _out, _ = run_tune("--no-compile", "-o", os.path.join(link, "motor_gen.h"), self.toml)
        print(f"measured: hostile -o through a symlinked folder onto a generated header: exit {code}")
        self.assertEqual(code, 0, lines)
        self.assertNotIn(b"/* stale */", sha(gen))  # replaced in the real folder
        self.assertTrue(os.path.islink(link))
        self.assertEqual(sorted(os.listdir(link)), ["motor_gen.h", "motor_hurst.h"])

    def test_the_default_target_should_never_follow_a_symlinked_folder(self) -> None:
        # firmware/motors/motor_<name>.h: no folder below the repository may be a link (it
        # would carry the write out of firmware/motors). In-process, on a scratch "repository".
        os.symlink(os.path.dirname(self.hand), os.path.join(self.dir, "firmware"))
        target = os.path.join(self.dir, "firmware", "motor_gen.h")
        with self.assertRaises(InputError) as cm:
            safeio.Output(target, "name", root=self.dir)
        print(f"measured: hostile default target through a symlinked folder: {cm.exception}")
        self.assertIn("symbolic link", str(cm.exception))
        safeio.Output(target, "-o")  # named by the user: accepted

    def test_a_symlink_target_should_be_refused(self) -> None:
        gen = self.generated()
        link = os.path.join(self.dir, "motor_link.h")
        os.symlink(gen, link)
        before = sha(gen)
        code, lines, _, _ = run_tune("--no-compile", "-o", link, self.toml)
        self.one_line("-o a symbolic link to a generated header", code, lines, 2, "symbolic link")
        self.assertEqual(sha(gen), before)
        self.assertTrue(os.path.islink(link))

    def test_a_read_only_header_should_be_refused(self) -> None:
        gen = self.generated()
        os.chmod(gen, 0o444)
        before = sha(gen)
        code, lines, _, _ = run_tune("--no-compile", "-o", gen, self.toml)
        self.one_line("-o a read-only generated header", code, lines, 2, "read-only")
        self.assertEqual(sha(gen), before)

    def test_odd_output_paths_should_be_written_and_echoed_escaped(self) -> None:
        # a file name that is not UTF-8 (with a UTF-8 terminal: the print used to fail after the
        # write, exit 3) or holds a newline: written, and named on one escaped line
        for label, name, shown in (("a byte that is not UTF-8", "\udcfd.h", "\\udcfd.h"),
                                   ("a newline", "a\nb.h", "a\\nb.h"), ("an escape sequence", "\x1b[2J.h", "\\x1b")):
            with self.subTest(label):
                code, lines, out, _ = run_tune("--no-compile", "-o", name, self.toml, env={"PYTHONIOENCODING": "utf-8"},
                                               cwd=self.dir)
                print(f"measured: hostile -o with {label}: exit {code}: {out.splitlines()[0] if out else ''}")
                self.assertEqual(code, 0, lines)
                self.assertTrue(os.path.exists(os.path.join(os.fsencode(self.dir), os.fsencode(name))))
                self.assertEqual(len(out.splitlines()), 3, out)
                self.assertTrue(out.startswith("tune: wrote " + shown), out)
                self.assertNotIn("\x1b", out)

    def test_a_path_gcc_cannot_name_in_a_string_should_still_be_compiled(self) -> None:
        # MC_MOTOR_HEADER is a string literal gcc's #include takes without escapes: a '"' or a
        # backslash in the path used to fail the compile check of a valid profile (exit 1)
        for label, folder in (("a double quote", 'q"x'), ("a backslash", "b\\y"), ("a newline", "n\nl")):
            with self.subTest(label):
                os.mkdir(os.path.join(self.dir, folder))
                out = os.path.join(self.dir, folder, "motor_q.h")
                code, lines, _, _ = run_tune("-o", out, self.toml)
                print(f"measured: hostile -o into a folder with {label}, compiled: exit {code}")
                self.assertEqual(code, 0, lines)
                code, lines, _, _ = run_tune("--check", out)
                self.assertEqual(code, 0, lines)

    def test_a_generated_header_should_be_replaced_with_the_umask_mode(self) -> None:
        for umask, mode in ((0o022, 0o644), (0o027, 0o640), (0o002, 0o664)):
            with self.subTest(oct(umask)):
                p = os.path.join(self.dir, f"motor_u{umask:o}.h")
                for attempt in ("new", "replace"):
                    code, lines, _, _ = run_tune("--no-compile", "-o", p, self.toml, umask=umask)
                    self.assertEqual(code, 0, lines)
                    got = stat.S_IMODE(os.stat(p).st_mode)
                    print(f"measured: hostile umask {umask:03o} ({attempt}): mode {got:03o}")
                    self.assertEqual(got, mode)
        self.assertEqual([f for f in os.listdir(self.dir) if f.endswith(".tmp")], [])


# ---- defect 3: names and descriptions break out into C -----------------------------------------

class NamesAndText(Hostile):
    def test_bad_names_should_be_refused_however_they_arrive(self) -> None:
        rel = os.path.relpath(os.path.join(self.dir, "escaped", "x"), MOTORS)
        names = [("path traversal (used to create folders, then crash)", "../" + rel),
                 ("a space (used to write a broken include guard)", "a b"), ("upper case", "Hurst"),
                 ("a newline", "ok\n#define X 1"), ("empty", ""), ("33 characters", "m" * 33),
                 ("a digit first", "1motor"), ("a dash", "my-motor"), ("a quote", 'x"y')]
        toml = self.write("m.toml", BASE_TOML)
        for label, name in names:
            with self.subTest(label):
                # the traversal without -o (the default path is where it escaped from); the
                # others with -o into the scratch folder, so nothing can land in firmware/motors
                out = [] if name.startswith("../") else ["-o", os.path.join(self.dir, "o.h")]
                code, lines, _, _ = run_tune("--no-compile", *out, "--name", name, toml)
                self.one_line(f"--name {label}", code, lines, 2, "--name")
                text = BASE_TOML.replace('name = "hostile_t"', f"name = {toml_str(name)}")
                code, lines, _, _ = run_tune("--no-compile", "-o", os.path.join(self.dir, "o.h"),
                                             self.write("n.toml", text))
                self.one_line(f"TOML name {label}", code, lines, 2, "name")
        self.assertFalse(os.path.exists(os.path.join(self.dir, "escaped")))
        self.assertFalse(os.path.exists(os.path.join(MOTORS, "motor_..")))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "o.h")))

    def test_a_description_that_would_break_out_of_c_should_be_refused(self) -> None:
        cases = [("a newline and a live #define (MOTOR_NAME's line ends, the next is a directive)",
                  "x\n#define MOTOR_SPEED_KP_A_PER_RPM 0 //"),
                 ("a comment end, a newline and a #define", "x */\n#define MOTOR_POLE_PAIRS 2\n/*"),
                 ("a newline alone", "line one\nline two"), ("a comment end", "x */ y"),
                 ("a comment start", "x /* y"), ("a double quote", 'x " y'), ("a backslash", "x \\ y"),
                 ("a trigraph ??/", "x ??/"), ("a tab", "x\ty"), ("a NUL", "x\x00y"),
                 ("a non-ASCII letter", "x \u00e9"), ("a line separator U+2028", "x\u2028y"),
                 ("500 characters", "x" * 500)]
        for label, desc in cases:
            with self.subTest(label):
                out = os.path.join(self.dir, "motor_d.h")
                text = BASE_TOML.replace('description = "hostile test motor"', f"description = {toml_str(desc)}")
                code, lines, _, _ = run_tune("--no-compile", "-o", out, self.write("d.toml", text))
                self.one_line(f"description with {label}", code, lines, 2, "description")
                self.assertFalse(os.path.exists(out))

    def test_a_file_name_with_a_comment_end_should_stay_inside_the_comment(self) -> None:
        # The description's path is written into the header's comment: a folder named "x *"
        # puts "*/" into it, the file's name a newline and a #define. It is escaped there.
        os.mkdir(os.path.join(self.dir, "x *"))
        odd = self.write(os.path.join("x *", "\n#define MOTOR_POLE_PAIRS 2\n.toml"), BASE_TOML)
        out = os.path.join(self.dir, "motor_f.h")
        code, lines, _, _ = run_tune("--no-compile", "-o", out, odd)
        self.assertEqual(code, 0, lines)
        with open(out, encoding="utf-8") as f:
            text = f.read()
        print("measured: hostile file name with '*/' and a newline: written, its comment escaped")
        # Outside the comments, every line of the header is a directive: nothing escaped them.
        code_only = re.sub(r"/\*.*?\*/", " ", text.replace("\\\n", " "), flags=re.S)
        stray = [ln for ln in code_only.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
        self.assertEqual(stray, [])
        self.assertEqual(len(re.findall(r"^#define MOTOR_POLE_PAIRS ", text, flags=re.M)), 1)
        self.assertIn("#define MOTOR_POLE_PAIRS 5", text)


def toml_str(s: str) -> str:
    """s as a TOML basic string (every control character escaped)."""
    out: list[str] = []
    for c in s:
        if c in ('"', "\\"):
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append(f"\\u{ord(c):04x}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


# ---- defect 4: tracebacks and useless profiles from bad descriptions ----------------------------

def _set(key: str, value: str) -> Callable[[str], str]:
    """BASE_TOML with `key = ...` replaced (or added to [motor] / [application])."""
    def f(text: str) -> str:
        new, n = re.subn(rf"^{re.escape(key)} = .*$", lambda _: f"{key} = {value}", text, count=1, flags=re.M)
        return new if n else text + f"{key} = {value}\n"
    return f


def _swap(old: str, new: str) -> Callable[[str], str]:
    """BASE_TOML with one text replaced."""
    return lambda text: text.replace(old, new)


HOSTILE_TOML: list[tuple[str, str | bytes | Callable[[str], str], str]] = [
    # (label, the file's text (str or bytes, or a function of BASE_TOML), a fragment of the answer)
    ("not UTF-8", b'name = "x\xff"\n', "UTF-8"),
    ("NUL bytes", b"\x00" * 64, "TOML"),
    ("empty file", "", "name"),
    ("a 5000-digit integer (used to give a traceback)", _set("pole_pairs", "9" * 5000), "too many digits"),
    ("arrays nested 5000 deep (used to give a traceback)", "a = " + "[" * 5000 + "]" * 5000 + "\n", "nested"),
    ("inline tables nested 2000 deep", "a = " + "{b = " * 2000 + "1" + "}" * 2000 + "\n", "nested"),
    ("100 kB of comments", "#" * 100_000 + "\n", "too large"),
    ("[[motor]] array of tables", _swap("[motor]", "[[motor]]"), "[motor] section"),
    ("motor = 5", 'name = "x"\nboard = "mclv"\nmotor = 5\n', "[motor] section"),
    ("application = []", "application = []\n" + BASE_TOML.split("[application]")[0], "[application] section"),
    ("name = 5", _set("name", "5"), "name"),
    ("name empty", _set("name", '""'), "name"),
    ("board traversal", _set("board", '"../../../etc/passwd"'), "board"),
    ("board upper case", _set("board", '"MCLV"'), "board"),
    ("pole_pairs 0", _set("pole_pairs", "0"), "motor.pole_pairs"),
    ("pole_pairs -3", _set("pole_pairs", "-3"), "motor.pole_pairs"),
    ("pole_pairs 33", _set("pole_pairs", "33"), "motor.pole_pairs"),
    ("pole_pairs 5.0", _set("pole_pairs", "5.0"), "motor.pole_pairs"),
    ("pole_pairs true", _set("pole_pairs", "true"), "motor.pole_pairs"),
    ("resistance 'nan ohm'", _set("resistance", '"nan ohm"'), "motor.resistance"),
    ("resistance_ohm = nan", _swap('resistance = "5.34 ohm"', "resistance_ohm = nan"), "motor.resistance"),
    ("resistance_ohm = inf", _swap('resistance = "5.34 ohm"', "resistance_ohm = inf"), "motor.resistance"),
    ("resistance_ohm = a 400-digit integer", _swap('resistance = "5.34 ohm"',
                                                                 "resistance_ohm = " + "9" * 400), "motor.resistance"),
    ("resistance 1e400 ohm", _set("resistance", '"1e400 ohm"'), "motor.resistance"),
    ("resistance 1e-300 ohm", _set("resistance", '"1e-300 ohm"'), "motor.resistance"),
    ("resistance 1e300 ohm", _set("resistance", '"1e300 ohm"'), "motor.resistance"),
    ("resistance as an array", _set("resistance", '["5.34 ohm"]'), "motor.resistance"),
    ("resistance as a table", _set("resistance", "{ value = 5.34 }"), "motor.resistance"),
    ("resistance as a date", _set("resistance", "1979-05-27"), "motor.resistance"),
    ("resistance 64 kB of spaces", _set("resistance", '"5.34' + " " * 60_000 + 'ohm"'), "motor.resistance"),
    ("resistance_kind 5", _set("resistance_kind", "5"), "motor.resistance_kind"),
    ("resistance twice", _swap('resistance = "5.34 ohm"', 'resistance = "5.34 ohm"\nresistance_ohm = 5.34'),
     "motor.resistance"),
    ("inductance 1e-300 H", _set("inductance", '"1e-300 H"'), "motor.inductance"),
    ("inductance 1e300 H", _set("inductance", '"1e300 H"'), "motor.inductance"),
    ("inductance 3.84 uH (too small for the PWM)", _set("inductance", '"3.84 uH"'), "motor.inductance"),
    ("back_emf 1e-300 V/krpm", _set("back_emf", '"1e-300 V/krpm"'), "motor.back_emf"),
    ("back_emf 1e300 V/rpm", _set("back_emf", '"1e300 V/rpm"'), "motor.back_emf"),
    ("back_emf in ohm", _set("back_emf", '"7.3 ohm"'), "motor.back_emf"),
    ("rated_current 1e-300 A", _set("rated_current", '"1e-300 A"'), "motor.rated_current"),
    ("rated_current 1e300 A", _set("rated_current", '"1e300 A"'), "motor.rated_current"),
    ("rated_speed 1e308 krpm (infinite; used to give a traceback)", _set("rated_speed", '"1e308 krpm"'),
     "motor.rated_speed"),
    ("rated_speed_rpm = inf", _swap('rated_speed = "2700 rpm"', "rated_speed_rpm = inf"),
     "motor.rated_speed"),
    ("rated_speed 0 rpm", _set("rated_speed", '"0 rpm"'), "motor.rated_speed"),
    ("rated_speed 1e9 rpm", _set("rated_speed", '"1e9 rpm"'), "motor.rated_speed"),
    ("max_speed 1e9 rpm", _set("max_speed", '"1e9 rpm"'), "application.max_speed"),
    ("max_speed 9000 rpm (beyond the bus)", _set("max_speed", '"9000 rpm"'), "application.max_speed"),
    ("min_speed above the top speed", _set("min_speed", '"6000 rpm"'), "application.min_speed"),
    ("peak_current below rated", _set("peak_current", '"1.0 A"'), "motor.peak_current"),
    ("inertia 7.5e-6 kg cm^2 (meant kg m^2: speed gains round to 0)", _set("inertia", '"7.5e-6 kg cm^2"'),
     "did you mean"),
    ("inertia 75 kg m^2 (meant g cm^2)", _set("inertia", '"75 kg m^2"'), "did you mean"),
    ("inertia 7.5e-6 g cm^2", _set("inertia", '"7.5e-6 g cm^2"'), "motor.inertia"),
    ("inertia 1e-300 kg m^2", _set("inertia", '"1e-300 kg m^2"'), "motor.inertia"),
    ("inertia_kgm2 = -1", _swap('inertia = "7.5e-6 kg m^2"', "inertia_kgm2 = -1"), "motor.inertia"),
    ("pwm_frequency 0 Hz", _set("pwm_frequency", '"0 Hz"'), "pwm_frequency"),
    ("pwm_frequency 1e300 kHz (used to give a traceback)", _set("pwm_frequency", '"1e300 kHz"'), "pwm_frequency"),
    ("pwm_frequency 20.5 kHz", _set("pwm_frequency", '"20.5 kHz"'), "pwm_frequency"),
    ("pwm_frequency 7 kHz (does not divide the clock)", _set("pwm_frequency", '"7 kHz"'), "pwm_frequency"),
    ("pwm_frequency -20 kHz", _set("pwm_frequency", '"-20 kHz"'), "pwm_frequency"),
    ("current_bandwidth 1e12 rad/s", _set("current_bandwidth", '"1e12 rad/s"'), "application.current_bandwidth"),
    ("current_bandwidth 1e-300 rad/s", _set("current_bandwidth", '"1e-300 rad/s"'), "application.current_bandwidth"),
    ("current_bandwidth 1 rad/s (gains round to 0)", _set("current_bandwidth", '"1 rad/s"'),
     "application.current_bandwidth"),
    ("fw_load_current 1e300 A", _set("fw_load_current", '"1e300 A"'), "application.fw_load_current"),
    ("start_load 1e300 N m", _set("start_load", '"1e300 N m"'), "application.start_load"),
    ("start_load 0.2 N m (beyond the current limit)", _set("start_load", '"0.2 N m"'), "application.start_load"),
    ("a key with a newline", lambda t: t + '"bad\\nkey" = 1\n', "unknown field"),
    ("a 60 kB key", _swap("[application]", '"' + "k" * 60_000 + '" = 1\n[application]'), "unknown field"),
    ("an unknown section", lambda t: t + "[motr]\nx = 1\n", "motr"),
    ("a unit with non-ASCII", _set("resistance", '"5.34 \u00f6hm"'), "motor.resistance"),
    ("a value with a control character", _set("resistance", '"5.34\\u0007 ohm"'), "motor.resistance"),
    ("current_kind 'peak\\n'", _set("current_kind", '"peak\\n#define X"'), "motor.current_kind"),
]


class DescriptionsNeverTraceback(Hostile):
    def test_every_hostile_description_should_get_one_line_and_no_file(self) -> None:
        out = os.path.join(self.dir, "motor_out.h")
        for label, src, fragment in HOSTILE_TOML:
            with self.subTest(label):
                data = src(BASE_TOML) if callable(src) else src
                p = self.write("h.toml", data)
                if os.path.exists(out):
                    os.unlink(out)
                code, lines, _, _ = run_tune("--no-compile", "-o", out, p)
                self.one_line(f"TOML {label}", code, lines, None, fragment)
                self.assertFalse(os.path.exists(out))
        print(f"measured: {len(HOSTILE_TOML)} hostile descriptions, each one line")

    def test_input_paths_that_are_not_files_should_be_refused(self) -> None:
        fifo = os.path.join(self.dir, "fifo.toml")
        os.mkfifo(fifo)
        for label, path, fragment in (("a directory", self.dir, "directory"),
                                      ("a fifo (used to block forever)", fifo, "fifo"),
                                      ("/dev/null", "/dev/null", "character device"),
                                      ("a missing file", os.path.join(self.dir, "none.toml"), "No such file")):
            with self.subTest(label):
                code, lines, _, _ = run_tune("--no-compile", "-o", os.path.join(self.dir, "o.h"), path)
                self.one_line(f"description file: {label}", code, lines, 2, fragment)

    def test_a_fault_of_the_tool_itself_should_still_be_one_line(self) -> None:
        # In-process: a bug (here an injected one) ends in one line and exit 3, not a traceback.
        saved = derive.derive

        def broken(desc: Description) -> Tuning:
            raise ZeroDivisionError(f"injected ({desc.name})")

        err = io.StringIO()
        derive.derive = broken
        try:
            with contextlib.redirect_stderr(err):
                code = cli.main(["--no-compile", "-o", os.path.join(self.dir, "o.h"), self.write("m.toml", BASE_TOML)])
        finally:
            derive.derive = saved
        lines = err.getvalue().strip().splitlines()
        self.one_line("an internal error (injected ZeroDivisionError)", code, lines, 3, "internal error")

    def test_command_line_errors_should_be_one_line(self) -> None:
        h = hurst075_path()
        toml = self.write("m.toml", BASE_TOML)
        out = os.path.join(self.dir, "o.h")
        for label, args, fragment in (
                ("an unknown option", ["--bogus"], "--bogus"), ("-o without a value", ["-o"], "-o"),
                ("no arguments", [], "no description given (usage: tools/tune/tune --help)"),
                # --check writes nothing: what would be ignored is refused
                ("--check with -o", ["--check", h, "-o", out], "-o"),
                ("--check with --name", ["--check", h, "--name", "x"], "--name"),
                ("--check with a description", ["--check", h, toml], "description"),
                ("--board without --check", ["--board", "mclv", "-o", out, toml], "--board")):
            with self.subTest(label):
                code, lines, _, _ = run_tune(*args)
                self.one_line(f"command line: {label}", code, lines, 2, fragment)
                self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
