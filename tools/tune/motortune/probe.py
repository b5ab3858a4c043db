# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""The core's numbers, from the C compiler: tools/tune's probe (probe/*.c).

tools/tune computes nothing the core computes. To learn what the core makes of
a board or a profile it compiles probe/probe_values.c against the real headers
(firmware/UserParms.h, firmware/mc_derived.h, boards/, the profile) with the
host C compiler, links it with probe/probe_main.c, runs it and reads the lines
it prints (`fact`, `text`, `row`). The core's own compile-time checks
(MC_CHECK, mc_derived.h) are the refusals: a check that fails is reported with
the parameter it names and the reason its line gives (CoreRefusal).

A profile is data, never code: before it is compiled its preprocessed text
(`cc -E -dD`) is screened (`screen`): #define and #undef lines only, upper-case
macro names, bodies made of numbers, names, strings and the operators of a
constant expression; no code, no #include, no #pragma, no #line. What passes
can only put numbers into probe_values.c's data (docs/tune.md, "Input safety").
"""

from __future__ import annotations

import functools
import os
import re
import shlex
import shutil
import subprocess
import tempfile
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from .units import NAME_RE, InputError, one_line

REPO = Path(__file__).resolve().parents[3]
PROBE_DIR = Path(__file__).resolve().parent / "probe"
FIRMWARE = REPO / "firmware"
BOARDS = REPO / "boards"

# The build's strict flags (CMakeLists.txt FOC_WARNINGS): what passes here passes there.
C_FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-Wconversion", "-Wsign-conversion", "-Wshadow"]
INCLUDES = [f"-I{REPO}/firmware", f"-I{REPO}/foc", f"-I{REPO}/smc_estimator", f"-I{PROBE_DIR}"]
TIMEOUT_S = 60.0  # one compiler or probe run; a well-formed one takes well under a second

# MC_MOTOR_HEADER names the profile in a string literal, which #include takes as it is (no
# escapes): the profile is copied into a scratch folder under this name.
CC_PROFILE = "tune_check_profile.h"
STUB_PROFILE = "tune_probe_motor.h"  # the empty motor profile of a board probe
DEFAULT_BOARD = "mclv"  # what boards/board.h selects without MC_BOARD_<BOARD> (make's default BOARD)

# ---- the compiler ------------------------------------------------------------------------


class NoCompiler(Exception):
    """No C compiler on PATH (or $CC names none)."""

    def __str__(self) -> str:
        return ("cc: no C compiler found ($CC, cc, gcc or clang): tools/tune compiles the core's headers to "
                "read them (Debian: apt-get install gcc)")


@functools.cache
def find_cc() -> tuple[str, ...]:
    """$CC (split as the shell would), else cc, gcc or clang from PATH."""
    env = os.environ.get("CC", "").strip()
    if env:
        words = shlex.split(env)
        exe = shutil.which(words[0]) if words else None
        if exe is not None:
            return (exe, *words[1:])
    for name in ("cc", "gcc", "clang"):
        exe = shutil.which(name)
        if exe is not None:
            return (exe,)
    raise NoCompiler()


@functools.cache
def _is_clang(cc: tuple[str, ...]) -> bool:
    try:
        out = subprocess.run([*cc, "--version"], capture_output=True, text=True, timeout=TIMEOUT_S).stdout
    except (OSError, subprocess.TimeoutExpired):
        return False
    return "clang" in out


def _error_limit(cc: tuple[str, ...]) -> list[str]:
    """Every error, not the first 20: a board's refusals come among a missing motor's."""
    return ["-ferror-limit=0"] if _is_clang(cc) else ["-fmax-errors=0"]


@dataclass(frozen=True)
class Run:
    code: int
    out: str
    err: str


def _run(cmd: Sequence[str], what: str, cwd: Path | None = None) -> Run:
    env = {**os.environ, "LC_ALL": "C"}  # plain quotes in the diagnostics
    try:
        p = subprocess.run(list(cmd), capture_output=True, text=True, errors="replace", timeout=TIMEOUT_S,
                           env=env, cwd=cwd)
    except subprocess.TimeoutExpired:
        raise InputError(what, f"no answer within {TIMEOUT_S:.0f} s (the compiler or the probe hangs)") from None
    except OSError as e:
        raise InputError(what, f"cannot run {cmd[0]}: {e.strerror}") from None
    return Run(p.returncode, p.stdout, p.stderr)


# ---- the compiler's diagnostics ------------------------------------------------------------

_DIAG_RE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?:\d+:)? (?P<kind>fatal error|error|warning|note): "
                      r"(?P<msg>.*)$")
_NEG_WIDTH_RE = re.compile(r"negative width in bit-field '(\w+)'|bit-field '(\w+)' has negative width")
_MACRO_NOTE_RE = re.compile(r"(?:in expansion of|expanded from) macro '(\w+)'")
_CHECK_NAME_RE = re.compile(r"(?P<param>\w+?)__out_of_range(?:_for__(?P<other>\w+))?$")


@dataclass(frozen=True)
class Note:
    file: str
    line: int
    msg: str


@dataclass
class Diagnostic:
    """One error and the notes after it."""

    file: str
    line: int
    msg: str
    notes: list[Note] = field(default_factory=list)

    def places(self) -> Iterator[Note]:
        yield Note(self.file, self.line, self.msg)
        yield from self.notes


def diagnostics(stderr: str) -> list[Diagnostic]:
    out: list[Diagnostic] = []
    for ln in stderr.splitlines():
        m = _DIAG_RE.match(ln)
        if m is None:
            continue
        kind = m.group("kind")
        if kind == "note":
            if out:
                out[-1].notes.append(Note(m.group("file"), int(m.group("line")), m.group("msg")))
        elif kind != "warning":  # -Werror: every warning that counts is an error
            out.append(Diagnostic(m.group("file"), int(m.group("line")), m.group("msg")))
    return out


def label(path: str | Path) -> str:
    """A file's name in messages: relative to the repository when inside it."""
    a = os.path.abspath(path)
    return os.path.relpath(a, REPO) if a.startswith(str(REPO) + os.sep) else str(path)


@dataclass(frozen=True)
class Refusal:
    """A compile-time check of the core that failed: the parameter it names, the other one
    it names with it (MC_CHECK_FOR), its reason and where it is."""

    param: str
    other: str | None
    why: str
    where: str

    def line(self) -> str:
        with_other = f" (with {self.other})" if self.other else ""
        return f"{self.param}{with_other}: {self.why} ({self.where})"


class CoreRefusal(Exception):
    """The core refuses the values: its compile-time checks that failed, in their order."""

    def __init__(self, refusals: list[Refusal]) -> None:
        self.refusals = refusals
        more = f" (and {len(refusals) - 1} more)" if len(refusals) > 1 else ""
        super().__init__(one_line(f"{refusals[0].param}: {refusals[0].why}{more}"))


_STRING_RE = re.compile(r'"((?:[^"\\\n]|\\.)*)"')


def _check_call(path: str, line: int) -> tuple[int, str]:
    """The MC_CHECK(...) call starting at path:line: its last line and its reason (the
    string literals before its closing parenthesis)."""
    p = Path(path)
    if not p.is_file() or not str(p.resolve()).startswith(str(REPO) + os.sep):
        return line, "out of range"
    text = "\n".join(p.read_text(encoding="utf-8", errors="replace").splitlines()[line - 1:line + 30])
    depth, k, strings = 0, 0, []
    while k < len(text):
        c = text[k]
        if c == '"':
            m = _STRING_RE.match(text, k)
            if m is None:
                break
            strings.append(m.group(1))
            k = m.end()
            continue
        if c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth == 0:
                return line + text.count("\n", 0, k), " ".join("".join(strings).split()) or "out of range"
        k += 1
    return line, "out of range"


def refusals(errs: list[Diagnostic], evaluated_only: bool = False) -> list[Refusal]:
    """The failed checks among the errors: MC_CHECK's 'PARAM__out_of_range[_for__OTHER]',
    and the Q15 and smc.h range checks the core's checks did not name first. With
    evaluated_only, a check whose condition itself has an error (a value that is not there,
    as in a board probe without a motor) is no refusal."""
    failed = [(d, m.group(1) or m.group(2)) for d in errs if (m := _NEG_WIDTH_RE.search(d.msg))]
    others = [(os.path.normpath(p.file), p.line) for d in errs if not _NEG_WIDTH_RE.search(d.msg)
              for p in d.places()]
    out: list[Refusal] = []
    seen: set[tuple[str, str | None, str]] = set()
    for d, name in failed:
        c = _CHECK_NAME_RE.match(name)
        where = f"{label(d.file)}:{d.line}"
        if c is not None:
            end, why = _check_call(d.file, d.line)
            if evaluated_only and any(f == os.path.normpath(d.file) and d.line <= ln <= end for f, ln in others):
                continue
            r = Refusal(c.group("param"), c.group("other"), why, where)
        else:  # q15.h's q15_constant_out_of_range, smc.h's smc_...: the name says it
            if evaluated_only:
                continue
            r = Refusal(name, None, name.replace("_", " "), where)
        key = (r.param, r.other, r.where)
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


# ---- screening a profile -------------------------------------------------------------------

_LINEMARKER_RE = re.compile(r'^# (\d+) "((?:[^"\\]|\\.)*)"((?: \d+)*)\s*$')
_DEFINE_RE = re.compile(r"^#define (\w+)(\([^)]*\))?(?: (.*))?$")
_MACRO_NAME_RE = re.compile(r"[A-Z][A-Z0-9_]*")
_TOKEN_RE = re.compile(r"""\s*(?:(?P<num>\.?[0-9](?:[eEpP][+-]|[0-9A-Za-z_.])*)|(?P<id>[A-Za-z_]\w*)"""
                       r"""|(?P<str>"(?:[^"\\\n]|\\.)*")|(?P<op><<|>>|<=|>=|==|!=|&&|\|\||[-+*/%<>!~&|^?:()])"""
                       r"""|(?P<bad>\S))""")
# Names that would reach past a constant expression: a pragma, assembly, attributes.
_BANNED_IDS = frozenset({"_Pragma", "asm", "__asm", "__asm__", "__attribute", "__attribute__"})


@dataclass
class Screened:
    """What a profile defines, as the preprocessor read it in the build's context."""

    macros: dict[str, str] = field(default_factory=dict)  # name -> body
    lines: dict[str, int] = field(default_factory=dict)  # name -> line of its #define

    def string(self, name: str) -> str | None:
        """A macro whose body is one plain string literal (no escapes), or None."""
        m = re.fullmatch(r'"([^"\\]*)"', self.macros.get(name, "").strip())
        return m.group(1) if m else None


# The board's facts and its PWM (boards/board*.h): the HAL reads them without the profile, so a
# profile that set one would give the core one value and the HAL, which programs it, another.
_BOARD_FACT_RE = re.compile(r"(?:BOARD|PWM)_[A-Z0-9_]*")
# The directives a profile's own text may hold: its guard, its values, the PWM guard emit.py writes.
# (#include: what it would read is refused from the preprocessor's output, where it is live.)
_DIRECTIVES = frozenset({"define", "undef", "ifndef", "ifdef", "if", "elif", "else", "endif", "error",
                         "include"})
# The type names a cast in a constant expression may name.
_TYPE_NAMES = frozenset({"char", "short", "int", "long", "signed", "unsigned", "float", "double"} |
                        {f"{u}int{n}_t" for u in ("", "u") for n in (8, 16, 32, 64)})
_DIRECTIVE_RE = re.compile(r"^[ \t]*#[ \t]*([A-Za-z_]\w*)?", re.MULTILINE)
_COMMENT_OR_STRING_RE = re.compile(r"""/\*.*?\*/|//[^\n]*|"(?:[^"\\\n]|\\.)*"|'(?:[^'\\\n]|\\.)*'""", re.DOTALL)


def _tokens(body: str, name: str, where: str) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    pos = 0
    while pos < len(body):
        m = _TOKEN_RE.match(body, pos)
        if m is None:  # only white space left
            break
        pos = m.end()
        kind = m.lastgroup or "bad"
        if kind == "bad":
            raise InputError(where, f"{name}: {m.group('bad')!r} is not part of a constant expression (a "
                                    f"profile's values are numbers, names, strings and arithmetic)")
        out.append((kind, m.group(kind)))
    return out


def _body_ok(name: str, body: str, where: str, params: frozenset[str] = frozenset(),
             function_macros: frozenset[str] = frozenset()) -> None:
    """A value is numbers, macro names and arithmetic (or, whole, string literals): a name that
    is called must be a function-like macro or one of this macro's parameters, and a lower-case
    name can only be a parameter (anything else would be a C function the program calls)."""
    toks = _tokens(body, name, where)
    for i, (kind, tok) in enumerate(toks):
        if kind != "id":
            continue
        if tok in _BANNED_IDS:
            raise InputError(where, f"{name}: {tok} is not part of a constant expression")
        called = i + 1 < len(toks) and toks[i + 1] == ("op", "(")
        if tok in params:
            continue
        if called and tok not in function_macros:
            raise InputError(where, f"{name}: {one_line(tok, 40)}(...) is a call, not a value (a profile's "
                                    f"values are numbers and arithmetic; it would run in every program that "
                                    f"reads {name})")
        if not _MACRO_NAME_RE.fullmatch(tok) and tok != "defined" and not (tok in _TYPE_NAMES and not called):
            raise InputError(where, f"{name}: {one_line(tok, 40)} is not a macro (a profile's values are numbers, "
                                    f"upper-case macro names and arithmetic)")
    strings = [t for k, t in toks if k == "str"]
    if strings and len(strings) != len(toks):
        raise InputError(where, f"{name}: a string is a value on its own (a name), not part of an expression")


def directives_ok(text: str, shown: str) -> None:
    """The profile's own text: the directives the preprocessor would carry out and not show in
    its output (#pragma GCC poison, #pragma weak, #line) are refused before it runs."""
    plain = _COMMENT_OR_STRING_RE.sub(lambda m: "".join(c if c == "\n" else " " for c in m.group(0)), text)
    for m in _DIRECTIVE_RE.finditer(plain):
        d = m.group(1) or ""
        if d and d not in _DIRECTIVES:
            line = plain.count("\n", 0, m.start()) + 1
            raise InputError(f"{shown}:{line}", f"#{one_line(d, 20)}: a motor profile holds #define lines (and "
                                                f"its guard) only")


def screen(cpp_out: str, copy: Path, shown: str) -> Screened:
    """Checks the `cc -E -dD` text of a translation unit that includes the profile (copied
    to `copy`, named `shown` in messages) and returns what the profile defines. InputError
    for anything but #define and #undef lines of constant expressions."""
    target = os.path.normpath(copy)
    current, line = "", 0
    inside: list[bool] = []  # per open file: is it the profile?
    found = Screened()
    function_macros = frozenset(d.group(1) for t in cpp_out.splitlines()
                                if (d := _DEFINE_RE.match(t)) is not None and d.group(2) is not None)
    for text in cpp_out.splitlines():
        m = _LINEMARKER_RE.match(text)
        if m is not None:
            name = os.path.normpath(m.group(2).encode().decode("unicode_escape"))
            flags = m.group(3).split()
            in_profile = current == target
            if "1" in flags:
                if in_profile:
                    raise InputError(f"{shown}:{line - 1}", f"#include of {one_line(m.group(2), 60)}: a motor "
                                     f"profile holds its own values (tools/tune checks the profile, the build "
                                     f"would read the included file)")
                inside.append(name == target)
            elif "2" in flags:
                if inside:
                    inside.pop()
            elif in_profile and name != target:
                raise InputError(f"{shown}:{line}", "#line with a file name: a motor profile may not rename itself")
            current, line = name, int(m.group(1))
            continue
        here = f"{shown}:{line}"
        line += 1
        if current != target or not text.strip():
            continue
        if text.startswith("#define "):
            d = _DEFINE_RE.match(text)
            if d is None:
                raise InputError(here, f"cannot read {one_line(text, 60)!r}")
            name, body = d.group(1), d.group(3) or ""
            if not _MACRO_NAME_RE.fullmatch(name) or name.startswith("TUNE_"):
                raise InputError(here, f"{one_line(name, 40)}: a motor profile defines upper-case names (not "
                                       f"TUNE_*) only: its macros reach the core's code")
            if _BOARD_FACT_RE.fullmatch(name):
                raise InputError(here, f"{name}: a fact of the board and its PWM, which the HAL reads without "
                                       f"the profile: set it in boards/board_<board>.h or with -D, where both see it")
            params = frozenset(p.strip() for p in (d.group(2) or "()")[1:-1].split(",") if p.strip())
            _body_ok(name, body, here, params, function_macros)
            found.macros[name] = body
            found.lines[name] = line - 1
        elif text.startswith("#undef "):
            gone = text[len("#undef "):].strip()
            if gone not in found.macros:
                raise InputError(here, f"#undef {one_line(gone, 40)}: a motor profile removes only what it "
                                       f"defined itself (the board's and UserParms.h's values stay)")
            continue
        elif text.startswith("#"):
            raise InputError(here, f"{one_line(text.split()[0], 20)}: a motor profile holds #define lines only")
        else:
            raise InputError(here, f"C code in a motor profile ({one_line(text.strip(), 40)!r}): it holds "
                                   f"#define lines only")
    return found


# ---- one probe run --------------------------------------------------------------------------


@dataclass(frozen=True)
class Row:
    """A line of the --check table: the value, the integer the core holds, that integer back
    in the unit (None when the core holds no integer for it)."""

    name: str
    eng: float
    unit: str
    q: int | None
    decoded: float | None
    note: str


@dataclass
class Output:
    facts: dict[str, float] = field(default_factory=dict)
    texts: dict[str, str] = field(default_factory=dict)
    rows: list[Row] = field(default_factory=list)

    def fact(self, name: str) -> float:
        if name not in self.facts:
            raise InputError(name, "the probe did not print it (tools/tune and its probe disagree)")
        return self.facts[name]


def _unescape(s: str) -> str:
    return re.sub(r"\\x([0-9a-f]{2})", lambda m: chr(int(m.group(1), 16)), s)


def parse_output(text: str) -> Output:
    out = Output()
    for ln in text.splitlines():
        f = ln.split("\t")
        if f[0] == "fact" and len(f) == 3:
            out.facts[f[1]] = float(f[2])
        elif f[0] == "text" and len(f) == 3:
            out.texts[f[1]] = _unescape(f[2])
        elif f[0] == "row" and len(f) == 7:
            q = None if f[4] == "-" else int(f[4])
            dec = None if f[5] == "-" else float(f[5])
            out.rows.append(Row(f[1], float(f[2]), f[3], q, dec, f[6]))
    return out


@dataclass(frozen=True)
class Build:
    """The -D options of one configuration: the board, the motor header, a PWM frequency."""

    board: str
    motor_header: str
    pwm_hz: int | None = None

    def defines(self) -> list[str]:
        out = [f"-DMC_BOARD_{self.board.upper()}", f'-DMC_MOTOR_HEADER="{self.motor_header}"']
        if self.pwm_hz is not None:
            out.append(f"-DPWM_FREQUENCY_HZ={self.pwm_hz}L")
        return out


@contextmanager
def scratch() -> Iterator[Path]:
    with tempfile.TemporaryDirectory(prefix="tune_probe_") as d:
        yield Path(d)


def _compile(cc: tuple[str, ...], args: list[str], what: str, tmp: Path) -> Run:
    return _run([*cc, *C_FLAGS, *INCLUDES, "-iquote", str(tmp), *args], what)


def _probe(cc: tuple[str, ...], build: Build, mode: list[str], tmp: Path, what: str) -> Output:
    """Compiles probe_values.c (which must compile: the caller checked), links and runs it."""
    values, main, exe = tmp / "values.o", tmp / "main.o", tmp / "probe"
    for src, obj, defs in ((PROBE_DIR / "probe_values.c", values, build.defines()),
                           (PROBE_DIR / "probe_main.c", main, [])):
        r = _compile(cc, [*defs, *mode, "-c", str(src), "-o", str(obj)], what, tmp)
        if r.code != 0:
            raise _compile_error(r, what)
    r = _run([*cc, str(values), str(main), "-o", str(exe)], what)
    if r.code != 0:
        raise _compile_error(r, what)
    r = _run([str(exe)], what, cwd=tmp)
    if r.code != 0:
        raise InputError(what, f"the probe failed: {one_line(r.err or str(r.code), 120)}")
    return parse_output(r.out)


def _compile_error(r: Run, what: str) -> InputError:
    errs = diagnostics(r.err)
    if errs:
        d = errs[0]
        return InputError(what, f"{label(d.file)}:{d.line}: {d.msg}")
    tail = r.err.strip().splitlines()
    return InputError(what, f"compile failed: {tail[-1] if tail else r.code}")


# ---- a board ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Limits:
    """The ranges the core checks derived values against (probe_facts.h, mc_derived.h)."""

    kp_max: float
    ki_max: float
    lock_periods_max: float
    ol_damp_periods_max: float
    ol_damp_counts_per_period: float
    ramp_step_inc_min: float
    deadtime_band_max_fraction: float
    dtm_lock_bands: float
    speed_fs_top_fraction: float


@dataclass(frozen=True)
class Board:
    """A board with UserParms.h's settings as the core compiles them."""

    id: str  # the name in boards/board_<id>.h
    name: str  # BOARD_NAME
    fcy: int
    fpwm: int
    duty_max: int
    i_fs: float
    trip_reach: float  # the largest trip both polarities reach (MC_TRIP_REACH_A)
    vbus: float
    vbus_fs: float
    v_fs: float
    adc_bits: int
    deadtime_ns: float
    dt_counts: int
    duty_sample_max: int
    loop_hz: int
    vlim_fraction: float
    speed_ramp_rpm_s: float
    stall_speed_error_rpm: float
    emf_fs_ratio: float
    limits: Limits


def board_header(board: str) -> Path:
    """boards/board_<board>.h, or InputError naming the boards there are."""
    if not NAME_RE.fullmatch(board):
        raise InputError("board", f"{board[:40]!r}: a board name is lower-case letters, digits and _")
    path = BOARDS / f"board_{board}.h"
    if not path.is_file():
        have = sorted(f.name[6:-2] for f in BOARDS.glob("board_*.h"))
        raise InputError("board", f"no boards/board_{board}.h (boards: {', '.join(have)})")
    return path


def _unevaluated_refusals(cc: tuple[str, ...], build: Build, tmp: Path, what: str) -> list[Refusal]:
    """The core's checks that fail with a partial profile (its file in tmp): those whose
    conditions name only values that are there; the others fail for the values missing."""
    r = _compile(cc, [*build.defines(), "-DTUNE_PROBE_BOARD", "-DTUNE_PROBE_CHECK", *_error_limit(cc),
                      "-fsyntax-only", str(PROBE_DIR / "probe_values.c")], what, tmp)
    return refusals(diagnostics(r.err), evaluated_only=True)


@functools.cache
def board(board_id: str, pwm_hz: int | None = None) -> Board:
    """The board's values (at pwm_hz, else its PWM_FREQUENCY_HZ). CoreRefusal when the
    core's checks of the board and the PWM alone fail."""
    board_header(board_id)
    cc = find_cc()
    build = Build(board_id, STUB_PROFILE, pwm_hz)
    what = f"boards/board_{board_id}.h"
    with scratch() as tmp:
        (tmp / STUB_PROFILE).write_text("/* no motor: tools/tune reads the board */\n", encoding="ascii")
        failed = _unevaluated_refusals(cc, build, tmp, what)
        if failed:
            raise CoreRefusal(failed)
        out = _probe(cc, build, ["-DTUNE_PROBE_BOARD"], tmp, what)
    f = out.fact
    limits = Limits(f("MC_KP_MAX"), f("MC_KI_MAX"), f("MC_LOCK_PERIODS_MAX"), f("MC_OL_DAMP_PERIODS_MAX"),
                    f("MC_OL_DAMP_COUNTS_PER_PERIOD"), f("MC_RAMP_STEP_INC_MIN"),
                    f("MC_DEADTIME_BAND_MAX_FRACTION"), f("MC_DTM_LOCK_BANDS"), f("MC_SPEED_FS_TOP_FRACTION"))
    return Board(id=board_id, name=out.texts.get("BOARD_NAME", board_id), fcy=int(f("BOARD_FCY_HZ")),
                 fpwm=int(f("PWM_FREQUENCY_HZ")), duty_max=int(f("PWM_DUTY_MAX")), i_fs=f("BOARD_I_FULLSCALE_A"),
                 trip_reach=f("MC_TRIP_REACH_A"),
                 vbus=f("BOARD_VBUS_NOMINAL_V"), vbus_fs=f("BOARD_VBUS_FULLSCALE_V"),
                 v_fs=f("MC_VOLTAGE_FULLSCALE_V"), adc_bits=int(f("BOARD_ADC_BITS")),
                 deadtime_ns=f("PWM_DEADTIME_NS"), dt_counts=int(f("MC_DT_COUNTS")),
                 duty_sample_max=int(f("MC_DUTY_SAMPLE_MAX")), loop_hz=int(f("MC_SPEED_LOOP_HZ")),
                 vlim_fraction=f("MC_VOLTAGE_LIMIT_FRACTION"), speed_ramp_rpm_s=f("MC_SPEED_RAMP_RPM_PER_S"),
                 stall_speed_error_rpm=f("MC_STALL_SPEED_ERROR_RPM"), emf_fs_ratio=f("SMC_EMF_FS_RATIO"),
                 limits=limits)


def partial_refusals(b: Board, values: dict[str, float]) -> list[Refusal]:
    """The core's checks on a board that fail for some of a profile's values alone (the
    motor's data, before anything is derived from it). `values`: macro -> number."""
    cc = find_cc()
    build = Build(b.id, STUB_PROFILE, b.fpwm)
    with scratch() as tmp:
        lines = [f"#define {k} {v!r}" for k, v in values.items()]
        (tmp / STUB_PROFILE).write_text("\n".join(lines) + "\n", encoding="ascii")
        return _unevaluated_refusals(cc, build, tmp, f"boards/board_{b.id}.h")


# ---- a profile ---------------------------------------------------------------------------------


def pwm_guard_message(hz: int) -> str:
    """The #error of a profile derived for hz when the build runs another PWM frequency
    (emit.py writes it; _preprocess reads the frequency back from it)."""
    return f"PWM_FREQUENCY_HZ: this profile was derived for {hz} Hz (build with -DPWM_FREQUENCY_HZ={hz}L)"


_PWM_GUARD_RE = re.compile(r"this profile was derived for (\d+) Hz \(build with -DPWM_FREQUENCY_HZ=\d+L\)")


@dataclass
class Profile:
    """A profile as the core compiles it: its table (rows), facts and texts, or the checks
    it fails (refused, in their order; then rows is empty)."""

    build: Build
    out: Output
    refused: list[Refusal]
    macros: Screened


def _preprocess(cc: tuple[str, ...], build: Build, tmp: Path, shown: str) -> tuple[Build, Screened]:
    """cc -E -dD of probe_values.c with the profile, screened; a profile derived for another
    PWM frequency (emit.py's #error) is read again at that frequency."""
    copy = tmp / CC_PROFILE
    directives_ok(copy.read_text(encoding="utf-8"), shown)
    for _ in range(2):
        r = _compile(cc, [*build.defines(), "-E", "-dD", str(PROBE_DIR / "probe_values.c")], shown, tmp)
        if r.code == 0:
            return build, screen(r.out, copy, shown)
        errs = diagnostics(r.err)
        pwm = next((m for d in errs if (m := _PWM_GUARD_RE.search(d.msg))), None)
        if pwm is None or build.pwm_hz is not None:
            raise _profile_error(errs, r, copy, shown, Screened())
        build = Build(build.board, build.motor_header, int(pwm.group(1)))
    raise InputError(shown, "the preprocessor refuses it")  # not reached: the second run has the PWM


def _profile_error(errs: list[Diagnostic], r: Run, copy: Path, shown: str, macros: Screened) -> InputError:
    """An error that is not a failed check, named as the profile's: the line and the macro
    it is in, or the profile's macro whose expansion it is in."""
    if not errs:
        return _compile_error(r, shown)
    d = errs[0]
    target = os.path.normpath(copy)
    by_line = {ln: name for name, ln in macros.lines.items()}
    for p in d.places():
        if os.path.normpath(p.file) == target:
            name = by_line.get(p.line)
            where = f"{shown}:{p.line}"
            return InputError(where, f"{name}: {d.msg}" if name else d.msg)
    for n in d.notes:
        m = _MACRO_NOTE_RE.search(n.msg)
        if m is not None and m.group(1) in macros.macros:
            return InputError(m.group(1), f"{d.msg} ({label(d.file)}:{d.line})")
    # no token of the profile to point at (an empty body, a constant the compiler refuses
    # where it is used): the profile's first macro on the lines the diagnostic names
    for p in d.places():
        for name in re.findall(r"[A-Za-z_]\w*", _source_line(p.file, p.line)):
            if name in macros.macros:
                return InputError(name, f"{d.msg} ({label(p.file)}:{p.line})")
    return InputError(f"{label(d.file)}:{d.line}", d.msg)


def _source_line(path: str, line: int) -> str:
    p = Path(path)
    if not p.is_file() or not str(p.resolve()).startswith(str(REPO) + os.sep):
        return ""
    lines = p.read_text(encoding="utf-8", errors="replace").splitlines()
    return lines[line - 1] if 0 < line <= len(lines) else ""


def profile(text: str, board_id: str, shown: str, pwm_hz: int | None = None) -> Profile:
    """The core's values for a profile's text on a board (at pwm_hz when given, else at the
    frequency the profile was derived for). InputError when it is not a profile the
    preprocessor and the compiler can read; failed checks come back in .refused."""
    board_header(board_id)
    cc = find_cc()
    with scratch() as tmp:
        (tmp / CC_PROFILE).write_text(text, encoding="utf-8")
        build, macros = _preprocess(cc, Build(board_id, CC_PROFILE, pwm_hz), tmp, shown)
        r = _compile(cc, [*build.defines(), "-fsyntax-only", str(PROBE_DIR / "probe_values.c")], shown, tmp)
        if r.code != 0:
            errs = diagnostics(r.err)
            # the first error decides: a failed check, or values that are not C the core can
            # compute with (then the checks after it are consequences)
            failed = refusals(errs) if errs and _NEG_WIDTH_RE.search(errs[0].msg) else []
            if failed:
                return Profile(build, Output(), failed, macros)
            raise _profile_error(errs, r, tmp / CC_PROFILE, shown, macros)
        return Profile(build, _probe(cc, build, [], tmp, shown), [], macros)


def tune_board(text: str, shown: str) -> str | None:
    """The board a profile names (MOTOR_TUNE_BOARD), read as the build reads it (on the
    default board); None when it names none."""
    cc = find_cc()
    with scratch() as tmp:
        (tmp / CC_PROFILE).write_text(text, encoding="utf-8")
        _, macros = _preprocess(cc, Build(DEFAULT_BOARD, CC_PROFILE), tmp, shown)
    if "MOTOR_TUNE_BOARD" not in macros.macros:
        return None
    name = macros.string("MOTOR_TUNE_BOARD")
    if name is None:
        raise InputError("MOTOR_TUNE_BOARD", "must be a string naming the board")
    if not NAME_RE.fullmatch(name):
        raise InputError("MOTOR_TUNE_BOARD", f"{name[:40]!r}: a board name is lower-case letters, digits and _")
    return name


def compile_core(text: str, build: Build, shown: str) -> str | None:
    """cc -fsyntax-only of the core's files (firmware/mc*.c) with the profile (the core's
    own compile, the checks in its files too). None when it compiles, else its first
    error, in one line."""
    cc = find_cc()
    with scratch() as tmp:
        (tmp / CC_PROFILE).write_text(text, encoding="utf-8")
        b = Build(build.board, CC_PROFILE, build.pwm_hz)
        core = [str(f) for f in sorted(FIRMWARE.glob("mc*.c"))]
        r = _compile(cc, [*b.defines(), "-fsyntax-only", *core], shown, tmp)
        if r.code == 0:
            return None
        errs = diagnostics(r.err)
        copy = os.path.normpath(tmp / CC_PROFILE)
        if errs:
            d = errs[0]
            where = shown if os.path.normpath(d.file) == copy else label(d.file)
            return f"{where}:{d.line}: {d.msg}"
        tail = r.err.strip().splitlines()
        return tail[-1] if tail else "compile failed"
