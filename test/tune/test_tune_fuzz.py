# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Property-based fuzzing of tools/tune's input paths (hypothesis).

Random and hostile TOML texts go to describe.loads / describe.parse /
derive.derive and, when derive accepts them, generate.build (what
`tools/tune/tune <motor.toml>` runs); random and hostile header texts and
random macro bodies go to probe.profile (what `--check` runs: the screen, then
the C compiler). For every input:

  * the only exceptions are the tool's own InputError and Infeasible;
  * their message is one printable line of bounded length;
  * Python's eval and exec are never called (both are replaced by a trap
    while the tool runs), and no tools/ Python source calls them;
  * each input is answered within DEADLINE_MS;
  * a profile the tool writes holds PI gains of MIN_GAIN_COUNTS counts at least
    in the core's integers.

The examples are drawn from a fixed seed (derandomize) so CI is repeatable;
TUNE_FUZZ_RANDOM=1 draws new ones, TUNE_FUZZ_EXAMPLES=N sets how many per
property (the header properties, each a compile, take an eighth of that). The
whole file runs in about a minute. Without hypothesis (tools/requirements.txt)
it is skipped, and says so.

Run: .venv/bin/python -m unittest -v test_tune_fuzz   (from test/tune; CTest does it)
"""

from __future__ import annotations

import builtins
import contextlib
import itertools
import math
import os
import re
import sys
import tempfile
import time
import tokenize
import unittest
from collections.abc import Callable, Iterator
from typing import Any, TypeVar

from test_tune_unit import setUpModule  # noqa: F401 - skipped, with the reason, without a C compiler
from tune.motortune import derive, describe, generate, probe
from tune.motortune.derive import Infeasible
from tune.motortune.units import InputError

# hypothesis keeps a cache (and, unless told not to, a database) in .hypothesis/ of the
# working directory, which CTest makes the source folder: keep it in the scratch folder.
os.environ.setdefault("HYPOTHESIS_STORAGE_DIRECTORY",
                      os.path.join(os.environ.get("TUNE_SCRATCH") or tempfile.gettempdir(), "hypothesis"))

try:
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st
except ImportError:  # CTest reports the test skipped (SKIP_REGULAR_EXPRESSION)
    raise unittest.SkipTest("hypothesis is not installed (tools/requirements.txt: run tools/bootstrap)") from None

T = TypeVar("T")
REPO = str(probe.REPO)
EXAMPLES = int(os.environ.get("TUNE_FUZZ_EXAMPLES", "200"))
HEADER_EXAMPLES = max(10, EXAMPLES // 8)
DEADLINE_MS = 20000  # per input; the tool answers in under a second (it compiles), a hang takes far longer


def fuzz(n: int) -> Callable[[Callable[..., None]], Callable[..., None]]:
    return settings(max_examples=n, deadline=None, database=None,
                    derandomize=os.environ.get("TUNE_FUZZ_RANDOM") != "1",
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


EXPECTED = (InputError, Infeasible)
MAX_MESSAGE = 400


class _Trap(Exception):
    pass


@contextlib.contextmanager
def no_eval() -> Iterator[None]:
    """eval and exec raise while the tool runs: a header or a description is data."""
    saved = builtins.eval, builtins.exec

    def trap_for(real: Callable[..., Any]) -> Callable[..., Any]:
        def trap(*a: Any, **k: Any) -> Any:
            # importing a module (a codec the first time it is used) runs its code through
            # exec from importlib: that is Python loading itself, not the tool's input
            if sys._getframe(1).f_globals.get("__name__", "").startswith("importlib"):
                return real(*a, **k)
            raise _Trap("tools/tune called eval or exec")
        return trap

    builtins.eval, builtins.exec = trap_for(saved[0]), trap_for(saved[1])
    try:
        yield
    finally:
        builtins.eval, builtins.exec = saved


def answer(case: unittest.TestCase, fn: Callable[..., T], *args: Any) -> T | Exception:
    """Runs the tool's entry point: returns its result or its own error, fails on anything
    else, on a message that is not one line, and on time."""
    t0 = time.monotonic()
    try:
        with no_eval():
            return fn(*args)
    except EXPECTED as e:
        msg = str(e)
        case.assertNotIn("\n", msg)
        case.assertNotIn("\r", msg)
        case.assertTrue(msg.isprintable(), repr(msg))
        case.assertLessEqual(len(msg), MAX_MESSAGE, msg)
        return e
    finally:
        case.assertLess(time.monotonic() - t0, DEADLINE_MS / 1000.0)


# ---- TOML descriptions --------------------------------------------------------------------

VALID = {
    ("", "name"): '"fuzz_t"', ("", "description"): '"fuzz motor"', ("", "board"): '"mclv"',
    ("", "pwm_frequency"): '"20 kHz"',
    ("motor", "pole_pairs"): "5", ("motor", "resistance"): '"5.34 ohm"',
    ("motor", "resistance_kind"): '"line-to-line"', ("motor", "inductance"): '"3.84 mH"',
    ("motor", "inductance_kind"): '"line-to-line"', ("motor", "back_emf"): '"7.3 V/krpm"',
    ("motor", "back_emf_kind"): '"peak line-to-line"', ("motor", "rated_current"): '"1.64 A"',
    ("motor", "current_kind"): '"peak"', ("motor", "rated_speed"): '"2700 rpm"',
    ("motor", "peak_current"): '"3.0 A"', ("motor", "inertia"): '"7.5e-6 kg m^2"',
    ("application", "max_speed"): '"5300 rpm"', ("application", "fw_load_current"): '"0.1 A"',
    ("application", "min_speed"): '"600 rpm"', ("application", "current_bandwidth"): '"3000 rad/s"',
    ("application", "start_load"): '"20 mN m"',
}
UNITS = ["ohm", "mohm", "H", "mH", "uH", "V/krpm", "V/rpm", "mV/rpm", "A", "mA", "rpm", "krpm", "kg m^2",
         "kg cm^2", "g cm^2", "Hz", "kHz", "rad/s", "N m", "mN m", "s", "ms", "%", "", "ohn", "\u03a9", "m\u00b2"]


def toml_str(s: str) -> str:
    out = []
    for c in s:
        if c in ('"', "\\"):
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F or 0xD800 <= ord(c) <= 0xDFFF:
            out.append(f"\\u{ord(c) if ord(c) < 0xD800 else 0xFFFD:04x}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


def toml_float(x: float) -> str:
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    r = repr(x)
    return r if any(c in r for c in ".en") else r + ".0"


numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-1e6, max_value=1e6),
    st.sampled_from([0.0, -0.0, 1e-300, 1e300, 5e-324, 1.7976931348623157e308, 1e-9, 1e9]),
    st.integers(min_value=-(10 ** 30), max_value=10 ** 30).map(float),
)
values = st.one_of(
    st.sampled_from(list(VALID.values())),
    st.tuples(numbers, st.sampled_from(UNITS)).map(lambda t: toml_str(f"{t[0]!r} {t[1]}".strip())),
    st.tuples(st.text(max_size=12), st.sampled_from(UNITS)).map(lambda t: toml_str(f"{t[0]} {t[1]}")),
    numbers.map(toml_float),
    st.integers().map(str),
    st.integers(min_value=10 ** 300, max_value=10 ** 400).map(str),
    st.text(max_size=40).map(toml_str),
    st.sampled_from(["true", "[]", '["5 ohm"]', "{}", "{ a = 1 }", "1979-05-27", '""', '"' + "9" * 400 + ' rpm"',
                     toml_str("x\n#define MOTOR_POLE_PAIRS 2 //"), toml_str("x */ y"), toml_str('a"b'),
                     toml_str("../../../tmp/evil"), toml_str("a b"), toml_str("??/")]),
)
keys = st.one_of(st.sampled_from(sorted({k for _, k in VALID})),
                 st.sampled_from(["resistance_ohm", "inductance_mh", "inertia_kgm2", "rated_speed_rpm",
                                  "pole_pairs", "motor", "application", "x"]),
                 st.text(min_size=1, max_size=20))


# The unit and the nominal value of each numeric field: scaled by 10^-8..10^8, they reach
# every branch of derive (the plausibility limits, Infeasible, the gain checks).
NOMINAL = {("", "pwm_frequency"): (20.0, "kHz"), ("motor", "resistance"): (5.34, "ohm"),
           ("motor", "inductance"): (3.84, "mH"), ("motor", "back_emf"): (7.3, "V/krpm"),
           ("motor", "rated_current"): (1.64, "A"), ("motor", "rated_speed"): (2700.0, "rpm"),
           ("motor", "peak_current"): (3.0, "A"), ("motor", "inertia"): (7.5e-6, "kg m^2"),
           ("application", "max_speed"): (5300.0, "rpm"), ("application", "fw_load_current"): (0.1, "A"),
           ("application", "min_speed"): (600.0, "rpm"), ("application", "current_bandwidth"): (3000.0, "rad/s"),
           ("application", "start_load"): (0.02, "N m")}


@st.composite
def scaled(draw: st.DrawFn, key: tuple[str, str]) -> str:
    if key == ("motor", "pole_pairs"):
        return str(draw(st.integers(-2, 40)))
    x, unit = NOMINAL[key]
    e = draw(st.floats(min_value=-8.0, max_value=8.0))
    return toml_str(f"{x * 10.0 ** e:.6g} {unit}")


@st.composite
def descriptions(draw: st.DrawFn) -> str:
    """A description built from the valid one: up to four fields scaled over 16 decades,
    replaced by hostile values or dropped; sometimes random keys; sometimes a section
    header mangled."""
    fields = dict(VALID)
    for _ in range(draw(st.integers(0, 4))):
        key = draw(st.sampled_from(sorted(fields)))
        how = draw(st.integers(0, 9))
        if how == 0:
            del fields[key]
        elif how <= 6 and (key in NOMINAL or key == ("motor", "pole_pairs")):
            fields[key] = draw(scaled(key))
        else:
            fields[key] = draw(values)
    if draw(st.integers(0, 4)) == 0:
        fields[(draw(st.sampled_from(["", "motor", "application"])), draw(keys))] = draw(values)
    lines = []
    for sec in ("", "motor", "application"):
        if sec:
            lines.append(f"[{sec}]" if draw(st.integers(0, 19)) else
                         draw(st.sampled_from([f"[[{sec}]]", f"{sec} = 5"])))
        for (s, k), v in fields.items():
            if s == sec:
                lines.append(f"{toml_str(k) if not re.fullmatch(r'[A-Za-z0-9_-]+', k) else k} = {v}")
    return "\n".join(lines) + "\n"


def derived(text: str) -> derive.Tuning:
    return derive.derive(describe.parse(describe.loads(text)))


def built(text: str) -> generate.Generated:
    return generate.build(describe.parse(describe.loads(text)), "fuzz", "motor_fuzz_t.h")


class FuzzDescriptions(unittest.TestCase):
    @fuzz(EXAMPLES)
    @given(descriptions())
    def test_mutated_descriptions_should_raise_only_the_tools_own_errors(self, text: str) -> None:
        r = answer(self, derived, text)
        if not isinstance(r, Exception):  # accepted: then the profile is judged by the core
            g = answer(self, built, text)
            if isinstance(g, generate.Generated):
                for macro, fact in generate.GAIN_COUNTS.items():
                    self.assertGreaterEqual(g.profile.out.fact(fact), derive.MIN_GAIN_COUNTS, macro)

    @fuzz(EXAMPLES)
    @given(st.one_of(st.text(max_size=300), st.binary(max_size=300).map(lambda b: b.decode("latin-1"))))
    def test_random_text_should_raise_only_the_tools_own_errors(self, text: str) -> None:
        answer(self, derived, text)


# ---- headers ------------------------------------------------------------------------------

with open(os.path.join(REPO, "firmware", "motors", "motor_hurst.h"), encoding="utf-8") as _f:
    BASE_HEADER = _f.read()
MACROS = re.findall(r"^#define (\w+) ", BASE_HEADER, flags=re.M)

atoms = st.one_of(
    st.sampled_from(MACROS + ["BOARD_FCY_HZ", "PWM_FREQUENCY_HZ", "MC_SPEED_LOOP_HZ", "NOT_DEFINED", "defined",
                              "__import__", "__class__", "os", "system", "lambda", "if", "else", "int", "double"]),
    st.integers(min_value=-(10 ** 25), max_value=10 ** 25).map(str),
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.sampled_from(["0", "00", "0x1F", "0x", "08", "1e999", "1e-999", "2.5f", "10L", "10UL", "10LLU", "1.5e+3L",
                     ".5", "5.", "1..2", "0x1p3", "'a'", '"s"', "1" * 60, "9" * 25]),
)
ops = st.sampled_from(["+", "-", "*", "/", "%", "<", ">", "<=", ">=", "==", "!=", "&&", "||", "**", "<<", "&",
                       "|", "^", ".", ",", "=", "->", "?", ":"])


def _compose(children: st.SearchStrategy[str]) -> st.SearchStrategy[str]:
    return st.one_of(
        st.tuples(children, ops, children).map(lambda t: f"{t[0]} {t[1]} {t[2]}"),
        children.map(lambda c: f"({c})"),
        st.tuples(st.sampled_from(["-", "+", "!", "~", "(double)", "(int16_t)", "(uint8_t)", "(long)", "*"]),
                  children).map(lambda t: f"{t[0]}{t[1]}"),
        st.tuples(children, children, children).map(lambda t: f"{t[0]} ? {t[1]} : {t[2]}"),
        st.tuples(atoms, children).map(lambda t: f"{t[0]}({t[1]})"),
        st.tuples(children, children).map(lambda t: f"[{t[0]}][{t[1]}]"),
    )


expressions = st.recursive(atoms, _compose, max_leaves=40)
directives = st.one_of(
    st.sampled_from(["#if 0", "#if 1", "#else", "#endif", "#elif 1", "#ifdef MOTOR_RS_OHM", "#ifndef X",
                     "#if defined(MC_BOARD_MCHV)", "#if defined X && !defined(Y)", "#undef MOTOR_LS_H", "#pragma once",
                     "#error no", "#frob", "#include \"/etc/passwd\"", "#", "/*", "*/", "//", "\\", "#define",
                     "#define MOTOR_FW_ID_TABLE_A(X) X(1) X((2)) X(", "#define F(a) a", "#line 5"]),
    expressions.map(lambda e: f"#if {e}"),
    st.tuples(st.sampled_from(MACROS + ["NEW_ONE"]), expressions).map(lambda t: f"#define {t[0]} {t[1]}"),
)


@st.composite
def headers(draw: st.DrawFn) -> str:
    """motor_hurst.h with macro bodies replaced by random expressions and random
    directive lines inserted."""
    text = BASE_HEADER
    for _ in range(draw(st.integers(0, 3))):
        name = draw(st.sampled_from(MACROS))
        body = draw(expressions)
        line = f"#define {name} {body}"
        text = re.sub(rf"^#define {name} .*$", line.replace("\\", "\\\\"), text, count=1, flags=re.M)
    lines = text.split("\n")
    for _ in range(draw(st.integers(0, 4))):
        lines.insert(draw(st.integers(0, len(lines))), draw(directives))
    return "\n".join(lines)


class FuzzHeaders(unittest.TestCase):
    def check(self, text: str) -> probe.Profile | Exception:
        return answer(self, probe.profile, text, "mclv", "motor_fuzz.h")

    @fuzz(HEADER_EXAMPLES)
    @given(headers())
    def test_mutated_headers_should_raise_only_the_tools_own_errors(self, text: str) -> None:
        r = self.check(text)
        if isinstance(r, probe.Profile):  # a failed check is one line too (--check prints it)
            for f in r.refused:
                self.assertNotIn("\n", f.line())

    @fuzz(HEADER_EXAMPLES)
    @given(st.text(alphabet=st.characters(blacklist_categories=["Cs"]), max_size=400))
    def test_random_header_text_should_raise_only_the_tools_own_errors(self, text: str) -> None:
        self.check(text)

    @fuzz(HEADER_EXAMPLES)
    @given(expressions)
    def test_random_values_should_be_read_as_c_or_refused(self, body: str) -> None:
        line = f"#define MOTOR_RS_OHM {body}"
        self.check(re.sub(r"^#define MOTOR_RS_OHM .*$", line.replace("\\", "\\\\"), BASE_HEADER, count=1,
                          flags=re.M))


class NoEvalInTools(unittest.TestCase):
    def test_no_python_under_tools_should_call_eval_or_exec(self) -> None:
        found = []
        n = 0
        for root, dirs, files in os.walk(os.path.join(REPO, "tools")):
            dirs[:] = [d for d in dirs if d not in (".venv", "build", "__pycache__")]
            for fn in files:
                if not fn.endswith(".py"):
                    continue
                path = os.path.join(root, fn)
                with open(path, "rb") as f:
                    toks = list(tokenize.tokenize(f.readline))
                n += 1
                for a, b in itertools.pairwise(toks):
                    if a.type == tokenize.NAME and a.string in ("eval", "exec") and b.string == "(":
                        found.append(f"{os.path.relpath(path, REPO)}:{a.start[0]}")
        print(f"measured: {n} Python files under tools/, eval( / exec( calls: {len(found)}")
        self.assertEqual(found, [])


if __name__ == "__main__":
    unittest.main()
