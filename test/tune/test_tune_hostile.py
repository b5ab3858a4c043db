"""Hostile inputs to tools/tune, each with the answer it must get.

The review of tools/tune (docs/tune.md, "Input safety") found that --check ran
code from the header it read, that -o overwrote whatever it was given, that a
name or a description could break out into C, and that bad input gave
tracebacks or, worse, useless profiles. Every input of that review and more is
listed here with what the tool must answer: exactly one line on stderr that
starts with "tune: " and names the field or file, a non-zero exit, no
traceback, nothing written, nothing executed, within a time bound. Each
answer is printed ("measured: hostile ...") so ctest -V shows the list.

Everything runs the command (tools/tune/tune) in a subprocess on copies in a
scratch directory: never on firmware/ itself.

Run: python3 -m unittest -v test_tune_hostile   (from test/tune; CTest does it)
"""

import os
import re
import shutil
import stat
import subprocess
import sys
import time
import unittest

from test_tune_unit import HURST_TOML, scratch  # the unit tests' fixture (same folder)

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
TUNE = os.path.join(REPO, "tools", "tune", "tune")
MOTORS = os.path.join(REPO, "firmware", "motors")
TIMEOUT_S = 20.0  # per command; a well-behaved answer takes well under a second

# The Hurst description the unit tests use, under its own name and with a
# description (the hostile cases rewrite fields of it).
BASE_TOML = HURST_TOML.replace('name = "hurst_t"\n',
                               'name = "hostile_t"\ndescription = "hostile test motor"\n')


def run_tune(*args, umask=None, env=None, cwd=None):
    """(exit code, stderr lines, stdout, seconds); a hang is a failure, not a wait."""
    def pre():
        if umask is not None:
            os.umask(umask)
    t0 = time.monotonic()
    try:
        r = subprocess.run([sys.executable, TUNE, *args], capture_output=True, text=True, errors="replace",
                           timeout=TIMEOUT_S, preexec_fn=pre if umask is not None else None,
                           env=None if env is None else {**os.environ, **env}, cwd=cwd)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"tools/tune {' '.join(args)[:80]}: no answer within {TIMEOUT_S:.0f} s") from None
    return r.returncode, r.stderr.strip().splitlines(), r.stdout, time.monotonic() - t0


def replace_define(text, name, body):
    """The header with `#define name ...` given another body (the line must exist)."""
    new, n = re.subn(rf"^#define {name} .*$", lambda _: f"#define {name} {body}", text, count=1, flags=re.M)
    assert n == 1, name
    return new


def sha(path):
    with open(path, "rb") as f:
        return f.read()


class Hostile(unittest.TestCase):
    def setUp(self):
        self.dir = scratch()

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def one_line(self, label, code, lines, want_code=None, fragment=""):
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

    def write(self, name, data):
        p = os.path.join(self.dir, name)
        with open(p, "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode("utf-8"))
        return p


# ---- defect 1: --check executes the header it reads --------------------------------------

class CheckNeverExecutes(Hostile):
    """--check reads a header as data: no Python runs, #if 0 is honoured, the work is bounded."""

    @classmethod
    def setUpClass(cls):
        with open(os.path.join(MOTORS, "motor_hurst075.h"), encoding="utf-8") as f:
            cls.base = f.read()

    def payload(self, marker):
        # What the review used: Python that runs a shell command through eval. Every name
        # in it was also #defined (inside #if 0, where the compiler never looks), so the
        # old reader's name lookup let the expression through to eval.
        return (f"[c.__init__.__globals__['system']('touch {marker}') for c in ().__class__.__base__."
                f"__subclasses__() if c.__name__ == '_wrap_close'][0] * 0 + 2.67")

    def disguised(self, marker, guard):
        """The payload as MOTOR_RS_OHM inside `guard` (#if 0...), with every identifier of it
        #defined there too, before the real definitions."""
        pay = self.payload(marker)
        idents = sorted(set(re.findall(r"[A-Za-z_]\w*", pay)))
        block = (f"{guard}\n" + "".join(f"#define {i} 0\n" for i in idents)
                 + f"#define MOTOR_RS_OHM {pay}\n#endif\n")
        return self.base.replace("#define MOTOR_HURST075_H\n", "#define MOTOR_HURST075_H\n" + block, 1)

    def test_a_payload_inside_if_0_should_be_skipped_and_never_run(self):
        marker = os.path.join(self.dir, "PWNED")
        h = self.write("evil.h", self.disguised(marker, "#if 0"))
        if shutil.which("gcc"):  # the header is valid C: the compiler skips the block
            cmd = ["gcc", "-std=c99", "-fsyntax-only", "-Wall", "-Wextra", "-Werror", "-x", "c", h]
            r = subprocess.run(cmd, capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
        code, lines, out, _ = run_tune("--check", h)
        ran = "CREATED" if os.path.exists(marker) else "absent"
        print(f"measured: hostile payload in #if 0: exit {code}, marker file {ran}")
        self.assertFalse(os.path.exists(marker), "--check ran the header's code")
        self.assertEqual(code, 0, lines)
        self.assertIn("F (AN1078 Eq. 2: 1 - Ts R/L)           0.930469", out)  # the real R, 2.67 ohm, was read

    def test_payloads_in_other_skipped_groups_should_not_run(self):
        for guard in ("#ifdef NOT_DEFINED_ANYWHERE", "#if defined(MC_BOARD_MCHV)", "#ifndef MOTOR_HURST075_H",
                      "#if 1 - 1", "#if 0 && (1 / 0)"):
            with self.subTest(guard):
                marker = os.path.join(self.dir, "PWNED")
                h = self.write("evil.h", self.disguised(marker, guard))
                code, lines, _, _ = run_tune("--check", h)
                print(f"measured: hostile payload under '{guard}': exit {code}")
                self.assertFalse(os.path.exists(marker))
                self.assertEqual(code, 0, lines)

    def test_a_live_payload_should_be_refused_in_one_line_and_never_run(self):
        marker = os.path.join(self.dir, "PWNED")
        h = self.write("evil.h", self.disguised(marker, "#if 1"))
        code, lines, _, _ = run_tune("--check", h)
        self.assertFalse(os.path.exists(marker), "--check ran the header's code")
        self.one_line("live payload (#if 1)", code, lines, 2, "MOTOR_RS_OHM")

    def test_each_non_c_expression_should_be_refused_naming_the_macro(self):
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
            ("bitwise shift (not used by any header)", "(1 << 2)", "MOTOR_RS_OHM"),
            ("comma operator", "(1, 2.67)", "MOTOR_RS_OHM"),
            ("undefined name", "NO_SUCH_MACRO * 2", "NO_SUCH_MACRO"),
            ("self-reference", "MOTOR_RS_OHM", "itself"),
            ("100 nested parentheses", "(" * 100 + "2.67" + ")" * 100, "nested"),
            ("3000 tokens", "+".join(["1"] * 1500), "tokens"),
            ("10000 unary minuses", "- " * 10000 + "2.67", "MOTOR_RS_OHM"),
            ("1e999", "1e999", "finite"),
            ("a 40-digit integer", "1" * 40, "64 bits"),
            ("1e300 * 1e300", "1e300 * 1e300", "finite"),
            ("division by zero", "(2.67 / 0)", "division by zero"),
            ("cast out of int16 range", "(int16_t)40000", "range"),
            ("empty body", "", "MOTOR_RS_OHM"),
        ]
        for label, body, fragment in cases:
            with self.subTest(label):
                h = self.write("bad.h", replace_define(self.base, "MOTOR_RS_OHM", body))
                code, lines, _, secs = run_tune("--check", h)
                self.one_line(f"--check MOTOR_RS_OHM {label}", code, lines, 2, fragment)
                self.assertLess(secs, 10.0)
                self.assertFalse(os.path.exists(marker))

    def test_a_macro_cycle_should_be_refused(self):
        text = replace_define(self.base, "MOTOR_RS_OHM", "MOTOR_LS_H")
        text = replace_define(text, "MOTOR_LS_H", "(MOTOR_RS_OHM * 1)")
        code, lines, _, _ = run_tune("--check", self.write("cycle.h", text))
        self.one_line("--check macro cycle", code, lines, 2, "itself")

    def test_a_fw_table_entry_payload_should_be_refused(self):
        text = self.base.replace("X(0.000)", "X(__import__('os').getcwd())", 1)
        code, lines, _, _ = run_tune("--check", self.write("fw.h", text))
        self.one_line("--check FW table entry payload", code, lines, 2, "MOTOR_FW_ID_TABLE_A")

    def test_directives_it_does_not_read_should_be_refused(self):
        cases = [
            ("#error in a read group", "#error stop here\n", "#error"),
            ("unknown directive", "#frobnicate 1\n", "frobnicate"),
            ("#endif without #if", "#endif\n", "#endif without #if"),
            ("#if without #endif", "#if 1\n", "#if without #endif"),
            ("#else twice", "#if 0\n#else\n#else\n#endif\n", "#else"),
            ("#if with a float", "#if 1.5\n#endif\n", "integer"),
            ("#ifdef without a name", "#ifdef\n#endif\n", "#ifdef"),
            ("unterminated comment (it swallows the guard's #endif)", "/* no end\n", "#if without #endif"),
            ("conflicting redefinition", "#define MOTOR_POLE_PAIRS 4\n", "MOTOR_POLE_PAIRS"),
            # the build would read the included file's values, --check would not: refused
            ("#include in a profile", '#include "motor_hurst.h"\n', "dir.h:"),
            ("a floating constant in #if (gcc refuses it)", "#if 1.5 > 1\n#endif\n", "floating constant"),
        ]
        for label, insert, fragment in cases:
            with self.subTest(label):
                text = self.base.replace("#endif /* MOTOR_HURST075_H */", insert + "#endif /* MOTOR_HURST075_H */")
                code, lines, _, _ = run_tune("--check", self.write("dir.h", text))
                self.one_line(f"--check {label}", code, lines, 2, fragment)
        code, lines, _, _ = run_tune("--check", self.write("dir.h", self.base + "/* no end\n"))
        self.one_line("--check unterminated comment at the end", code, lines, 2, "comment not closed")
        # inside #if 0 the compiler does not read the #include either
        text = self.base.replace("#endif /* MOTOR_HURST075_H */", '#if 0\n#include "x.h"\n#endif\n'
                                 "#endif /* MOTOR_HURST075_H */")
        code, lines, _, _ = run_tune("--no-compile", "--check", self.write("dir.h", text))
        self.assertEqual(code, 0, lines)


# ---- defect 4 (--check side): tracebacks on bad values --------------------------------------

class CheckBadValues(Hostile):
    @classmethod
    def setUpClass(cls):
        with open(os.path.join(MOTORS, "motor_hurst075.h"), encoding="utf-8") as f:
            cls.base = f.read()

    def test_values_that_leave_nothing_to_compute_should_be_one_line_naming_them(self):
        cases = [
            ("pole pairs 0", "MOTOR_POLE_PAIRS", "0", "MOTOR_POLE_PAIRS"),
            ("pole pairs 2.5", "MOTOR_POLE_PAIRS", "2.5", "MOTOR_POLE_PAIRS"),
            ("pole pairs -5", "MOTOR_POLE_PAIRS", "(-5)", "MOTOR_POLE_PAIRS"),
            ("PWM 0 Hz", "PWM_FREQUENCY_HZ", "0L", "PWM_FREQUENCY_HZ"),
            ("a string for R", "MOTOR_RS_OHM", '"2.67"', "MOTOR_RS_OHM"),
            ("board traversal", "MOTOR_TUNE_BOARD", '"../../../etc/x"', "board"),
        ]
        for label, name, body, fragment in cases:
            with self.subTest(label):
                code, lines, _, _ = run_tune("--check", self.write("v.h", replace_define(self.base, name, body)))
                self.one_line(f"--check {label}", code, lines, 2, fragment)

    def test_values_the_core_rejects_should_fail_the_check_in_one_stderr_line(self):
        cases = [
            ("observer band 0 (used to divide by zero)", "MOTOR_SMC_LINEAR_BAND_A", "0.0", "MOTOR_SMC_LINEAR_BAND_A"),
            ("speed Ki rounding to 0", "MOTOR_SPEED_KI_A_PER_RPM_S", "1e-9", "rounds to 0"),
            ("speed Kp rounding to 0 (inertia in g cm^2 read as kg m^2)", "MOTOR_SPEED_KP_A_PER_RPM", "2.58e-10",
             "rounds to 0"),
            ("current Ki 0", "MOTOR_CURRENT_KI_V_PER_AS", "0.0", "rounds to 0"),
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

    def test_values_beyond_every_range_should_fail_the_check_naming_the_macro(self):
        # each used to end in "internal error" (OverflowError, ValueError), exit 3
        cases = [
            ("open-loop damping 1e305 s (int of inf)", {"MOTOR_OL_DAMP_S": "1e305"}, "MOTOR_OL_DAMP_S"),
            ("ADC trigger 1e308 Tcy (int of -inf)", {"PWM_ADC_TRIGGER_TCY": "1e308"}, "PWM_ADC_TRIGGER_TCY"),
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
                self.one_line(f"--check {label}", code, lines, 1, fragment)
                self.assertIn("CHECK FAILED", out)

    def test_every_macro_set_to_every_extreme_should_give_only_input_errors(self):
        # In-process: each of the 80-odd macros the core reads (board, profile, UserParms.h),
        # set to each extreme in turn, and the pairs a range check joins: derive_core answers
        # with failed checks or an InputError, never another exception (--check's exit 3).
        sys.path.insert(0, os.path.join(REPO, "tools", "tune"))
        from motortune import cheader
        from motortune.units import InputError
        base = cheader.profile_env(os.path.join(MOTORS, "motor_hurst075.h"), "mclv").defs
        extremes = ["1e305", "-1e305", "1e308", "-1e308", "1e-305", "0", "0.0", "(-1)", "90000.0", "100000.0",
                    "32768", "4294967296.0", "9223372036854775807"]
        pairs = [("MC_ESTIMATOR_MIN_RPM", "MC_SPEED_FULLSCALE_RPM"), ("MOTOR_RAMP_END_RPM", "PWM_FREQUENCY_HZ"),
                 ("MOTOR_OL_DAMP_S", "PWM_FREQUENCY_HZ"), ("PWM_ADC_TRIGGER_TCY", "BOARD_FCY_HZ")]
        cases = [{n: v} for n in sorted(base.raw) for v in extremes]
        cases += [{a: v, b: w} for a, b in pairs for v in extremes for w in extremes]
        crashed = []
        for case in cases:
            defs = cheader.Defines({**base.raw, **case}, dict(base.xtables), set(base.funcs), dict(base.origin))
            try:
                cheader.derive_core(cheader.Env(defs))
            except InputError:
                pass
            except Exception as e:  # noqa: BLE001 - what the test looks for
                crashed.append(f"{case}: {type(e).__name__}: {e}")
        print(f"measured: hostile {len(cases)} extreme macro values in-process: {len(crashed)} exceptions")
        self.assertEqual(crashed, [])

    def test_files_that_are_not_headers_should_be_refused(self):
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
        code, lines, _, _ = run_tune("--check", os.path.join(MOTORS, "motor_hurst075.h"), "--board", "../x")
        self.one_line("--check --board ../x", code, lines, 2, "board")


# ---- defect 2: -o writes whatever it is given ------------------------------------------------

class OutputIsSafe(Hostile):
    def setUp(self):
        super().setUp()
        self.toml = self.write("m.toml", BASE_TOML)
        self.hand = os.path.join(self.dir, "motors", "motor_hurst.h")  # a copy: never the real one
        os.makedirs(os.path.dirname(self.hand))
        shutil.copy(os.path.join(MOTORS, "motor_hurst.h"), self.hand)

    def generated(self, name="motor_gen.h"):
        p = os.path.join(self.dir, name)
        code, lines, _, _ = run_tune("--no-compile", "-o", p, self.toml)
        self.assertEqual(code, 0, lines)
        return p

    def test_special_files_should_be_refused(self):
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

    def test_a_device_should_be_refused_before_anything_is_written(self):
        # In-process, on the check alone: a tool that regressed must not get the chance to
        # replace the machine's /dev/null (the review's tools/tune did, run as root).
        sys.path.insert(0, os.path.join(REPO, "tools", "tune"))
        from motortune import safeio
        from motortune.units import InputError
        for dev in ("/dev/null", "/dev/zero"):
            with self.subTest(dev):
                with self.assertRaises(InputError) as cm:
                    safeio.Output(dev, "-o")
                print(f"measured: hostile -o {dev}: {cm.exception}")
                self.assertIn("character device", str(cm.exception))
        self.assertTrue(stat.S_ISCHR(os.stat("/dev/null").st_mode))

    def test_a_missing_directory_should_be_refused_not_created(self):
        target = os.path.join(self.dir, "no", "such", "motor_x.h")
        code, lines, _, _ = run_tune("--no-compile", "-o", target, self.toml)
        self.one_line("-o into a missing directory", code, lines, 2, "-o")
        self.assertFalse(os.path.exists(os.path.join(self.dir, "no")))

    def test_a_hand_written_header_should_never_be_overwritten(self):
        before = sha(self.hand)
        code, lines, _, _ = run_tune("--no-compile", "-o", self.hand, self.toml)
        self.one_line("-o a hand-written header (a copy of motor_hurst.h)", code, lines, 2, "not generated")
        self.assertEqual(sha(self.hand), before)

    def test_a_symlinked_directory_the_user_names_should_be_followed_to_its_real_folder(self):
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
        code, lines, out, _ = run_tune("--no-compile", "-o", os.path.join(link, "motor_gen.h"), self.toml)
        print(f"measured: hostile -o through a symlinked folder onto a generated header: exit {code}")
        self.assertEqual(code, 0, lines)
        self.assertNotIn(b"/* stale */", sha(gen))  # replaced in the real folder
        self.assertTrue(os.path.islink(link))
        self.assertEqual(sorted(os.listdir(link)), ["motor_gen.h", "motor_hurst.h"])

    def test_the_default_target_should_never_follow_a_symlinked_folder(self):
        # firmware/motors/motor_<name>.h: no folder below the repository may be a link (it
        # would carry the write out of firmware/motors). In-process, on a scratch "repository".
        sys.path.insert(0, os.path.join(REPO, "tools", "tune"))
        from motortune import safeio
        from motortune.units import InputError
        os.symlink(os.path.dirname(self.hand), os.path.join(self.dir, "firmware"))
        target = os.path.join(self.dir, "firmware", "motor_gen.h")
        with self.assertRaises(InputError) as cm:
            safeio.Output(target, "name", root=self.dir)
        print(f"measured: hostile default target through a symlinked folder: {cm.exception}")
        self.assertIn("symbolic link", str(cm.exception))
        safeio.Output(target, "-o")  # named by the user: accepted

    def test_a_symlink_target_should_be_refused(self):
        gen = self.generated()
        link = os.path.join(self.dir, "motor_link.h")
        os.symlink(gen, link)
        before = sha(gen)
        code, lines, _, _ = run_tune("--no-compile", "-o", link, self.toml)
        self.one_line("-o a symbolic link to a generated header", code, lines, 2, "symbolic link")
        self.assertEqual(sha(gen), before)
        self.assertTrue(os.path.islink(link))

    def test_a_read_only_header_should_be_refused(self):
        gen = self.generated()
        os.chmod(gen, 0o444)
        before = sha(gen)
        code, lines, _, _ = run_tune("--no-compile", "-o", gen, self.toml)
        self.one_line("-o a read-only generated header", code, lines, 2, "read-only")
        self.assertEqual(sha(gen), before)

    def test_odd_output_paths_should_be_written_and_echoed_escaped(self):
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

    def test_a_path_gcc_cannot_name_in_a_string_should_still_be_compiled(self):
        # MC_MOTOR_HEADER is a string literal gcc's #include takes without escapes: a '"' or a
        # backslash in the path used to fail the compile check of a valid profile (exit 1)
        if shutil.which("gcc") is None:
            self.skipTest("no gcc")
        for label, folder in (("a double quote", 'q"x'), ("a backslash", "b\\y"), ("a newline", "n\nl")):
            with self.subTest(label):
                os.mkdir(os.path.join(self.dir, folder))
                out = os.path.join(self.dir, folder, "motor_q.h")
                code, lines, _, _ = run_tune("-o", out, self.toml)
                print(f"measured: hostile -o into a folder with {label}, compiled: exit {code}")
                self.assertEqual(code, 0, lines)
                code, lines, _, _ = run_tune("--check", out)
                self.assertEqual(code, 0, lines)

    def test_a_generated_header_should_be_replaced_with_the_umask_mode(self):
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
    def test_bad_names_should_be_refused_however_they_arrive(self):
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

    def test_a_description_that_would_break_out_of_c_should_be_refused(self):
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

    def test_a_file_name_with_a_comment_end_should_stay_inside_the_comment(self):
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


def toml_str(s):
    """s as a TOML basic string (every control character escaped)."""
    out = []
    for c in s:
        if c in ('"', "\\"):
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append(f"\\u{ord(c):04x}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


# ---- defect 4: tracebacks and useless profiles from bad descriptions ----------------------------

def _set(key, value):
    """BASE_TOML with `key = ...` replaced (or added to [motor] / [application])."""
    def f(text):
        new, n = re.subn(rf"^{re.escape(key)} = .*$", lambda _: f"{key} = {value}", text, count=1, flags=re.M)
        return new if n else text + f"{key} = {value}\n"
    return f


def _swap(old, new):
    """BASE_TOML with one text replaced."""
    return lambda text: text.replace(old, new)


HOSTILE_TOML = [
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
    def test_every_hostile_description_should_get_one_line_and_no_file(self):
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

    def test_input_paths_that_are_not_files_should_be_refused(self):
        fifo = os.path.join(self.dir, "fifo.toml")
        os.mkfifo(fifo)
        for label, path, fragment in (("a directory", self.dir, "directory"),
                                      ("a fifo (used to block forever)", fifo, "fifo"),
                                      ("/dev/null", "/dev/null", "character device"),
                                      ("a missing file", os.path.join(self.dir, "none.toml"), "No such file")):
            with self.subTest(label):
                code, lines, _, _ = run_tune("--no-compile", "-o", os.path.join(self.dir, "o.h"), path)
                self.one_line(f"description file: {label}", code, lines, 2, fragment)

    def test_a_fault_of_the_tool_itself_should_still_be_one_line(self):
        # In-process: a bug (here an injected one) ends in one line and exit 3, not a traceback.
        import contextlib
        import io
        sys.path.insert(0, os.path.join(REPO, "tools", "tune"))
        from motortune import cli, derive
        saved = derive.derive

        def broken(_desc):
            raise ZeroDivisionError("injected")

        err = io.StringIO()
        derive.derive = broken
        try:
            with contextlib.redirect_stderr(err):
                code = cli.main(["--no-compile", "-o", os.path.join(self.dir, "o.h"), self.write("m.toml", BASE_TOML)])
        finally:
            derive.derive = saved
        lines = err.getvalue().strip().splitlines()
        self.one_line("an internal error (injected ZeroDivisionError)", code, lines, 3, "internal error")

    def test_command_line_errors_should_be_one_line(self):
        h = os.path.join(MOTORS, "motor_hurst075.h")
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
