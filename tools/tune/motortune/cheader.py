"""Read the firmware's C profiles and compute what the core derives from them.

`read_headers` reads the object-like #define values of a list of headers the
way the preprocessor sees them: line splices, comments, and the conditionals
(#if 0, #ifdef, #ifndef, #if defined(X), #elif, #else, #endif, #undef) are
honoured, so a value inside #if 0 is not read and, through each value's
#ifndef guard, the first definition wins (the board, then the motor profile,
then UserParms.h's defaults; the build includes them in that order). A
directive it does not know stops the read with one line, and so does an
#include in a motor profile (the build would read that file, this reader
does not). An #if takes integers only, as the C preprocessor does. The X-macro
field-weakening table is read too. Values are computed by cexpr (numbers,
macros and C arithmetic only, never Python's eval). `derive_core` replays the
arithmetic of firmware/mc_derived.h, smc_estimator/smc.h (SMC_PARAMS_INIT)
and the checks of firmware/mc.c in double precision, giving every Q15 integer
the core will compile in and every range check it will apply.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from typing import Optional, Union

from . import cexpr, safeio
from .cexpr import ExprError, Number
from .units import NAME_RE, SQRT3, TWO_PI, InputError

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
FIRMWARE = os.path.join(REPO, "firmware")
BOARD_H = os.path.join(REPO, "boards", "board.h")  # the PWM settings, which the HAL reads too

MAX_HEADER_BYTES = 1 << 20  # the shipped headers are 3..25 kB
MAX_IF_NESTING = 64  # conditionals open at once in one file
MAX_TABLE_ENTRIES = 64  # X(...) entries of an X-macro (the core wants 16)

Value = Union[int, float, str]


@dataclass
class Defines:
    """What a list of headers defines: object-like macro bodies, X-macro tables'
    entries, the names of other function-like macros, and where each was defined."""

    raw: dict[str, str] = field(default_factory=dict)
    xtables: dict[str, list[str]] = field(default_factory=dict)
    funcs: set[str] = field(default_factory=set)
    origin: dict[str, str] = field(default_factory=dict)  # name -> "file:line"

    def defined(self, name: str) -> bool:
        return name in self.raw or name in self.xtables or name in self.funcs

    def undef(self, name: str) -> None:
        self.raw.pop(name, None)
        self.xtables.pop(name, None)
        self.origin.pop(name, None)
        self.funcs.discard(name)


def read_text(path: str, label: str = "") -> str:
    """The text of a header: a regular file of at most MAX_HEADER_BYTES, UTF-8."""
    return safeio.read_utf8(path, label or path, MAX_HEADER_BYTES)


_STRING_RE = re.compile(r'"(?:[^"\\\n]|\\.)*"?|\'(?:[^\'\\\n]|\\.)*\'?')
_LEX_RE = re.compile(r'/\*|//|["\'\n]')


def logical_lines(text: str, where: str = "") -> list[tuple[int, str]]:
    """(line number, text) of each logical line, as C's translation phases 1-3 make them:
    backslash-newline splices first, then each comment becomes one space (a block
    comment over several lines joins them, as in C); string and character literals
    are kept whole, so a '/*' inside one is not a comment."""
    phys = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    spliced: list[str] = []
    starts: list[int] = []  # physical line where each spliced line starts
    buf: list[str] = []
    start = 1
    for i, line in enumerate(phys, 1):
        if line.endswith("\\") and i < len(phys):
            buf.append(line[:-1])
            continue
        buf.append(line)
        spliced.append("".join(buf))
        starts.append(start)
        buf, start = [], i + 1
    src = "\n".join(spliced)
    out: list[tuple[int, str]] = []
    cur: list[str] = []
    idx = 0  # spliced line the scanner is on
    line_start = 0  # spliced line the current logical line started on
    pos = 0
    while True:
        m = _LEX_RE.search(src, pos)
        if m is None:
            cur.append(src[pos:])
            break
        cur.append(src[pos:m.start()])
        tok = m.group()
        if tok == "\n":
            out.append((starts[line_start], "".join(cur)))
            cur = []
            idx += 1
            line_start = idx
            pos = m.end()
        elif tok == "//":
            nl = src.find("\n", m.end())
            pos = len(src) if nl < 0 else nl
        elif tok == "/*":
            end = src.find("*/", m.end())
            if end < 0:
                raise InputError(f"{where}:{starts[idx]}", "comment not closed (/* without */)")
            idx += src.count("\n", m.start(), end)
            cur.append(" ")
            pos = end + 2
        else:  # a string or character literal, kept as it is
            lit = _STRING_RE.match(src, m.start())
            assert lit is not None  # the pattern matches any quote
            cur.append(lit.group())
            pos = lit.end()
    out.append((starts[line_start], "".join(cur)))
    return out


_DIRECTIVE_RE = re.compile(r"\s*#\s*([A-Za-z_]\w*)?\s*(.*)$", re.S)
_DEFINE_RE = re.compile(r"([A-Za-z_]\w*)(\([^)]*\))?(?:\s+(.*)|\s*)$", re.S)
_IDENT_ONLY_RE = re.compile(r"([A-Za-z_]\w*)\s*$")


def _x_entries(body: str, name: str, where: str) -> list[str]:
    """The entries of an X-macro table body, `X(a) X(b) ...` and nothing else (an entry may
    hold parentheses); each entry is an expression cexpr evaluates later."""
    out: list[str] = []
    i, n = 0, len(body)
    while True:
        while i < n and body[i].isspace():
            i += 1
        if i == n:
            return out
        m = re.compile(r"X\s*\(").match(body, i)
        if m is None:
            raise InputError(name, f"an X-macro table holds X(value) entries only, found {_short(body[i:], 20)!r} "
                                   f"({where})")
        depth, j = 1, m.end()
        while j < n and depth:
            depth += {"(": 1, ")": -1}.get(body[j], 0)
            j += 1
        if depth:
            raise InputError(name, f"unbalanced parentheses in the table ({where})")
        out.append(body[m.end():j - 1].strip())
        if len(out) > MAX_TABLE_ENTRIES:
            raise InputError(name, f"more than {MAX_TABLE_ENTRIES} entries ({where})")
        i = j


class _Cond:
    """One open conditional: whether its enclosing region is read, whether a branch was
    taken, whether #else was seen, where it opened."""

    def __init__(self, parent_on: bool, on: bool, where: str):
        self.parent_on, self.on, self.taken, self.in_else, self.where = parent_on, on, on, False, where


def _pp_condition(expr: str, defs: Defines, where: str, budget: cexpr.Budget) -> bool:
    """#if / #elif: an integer constant expression with defined(X); a name that is not
    a macro counts 0 (C's rule); a floating constant, in it or in a macro it expands, is
    refused (as gcc refuses `#if 1.5 > 1`)."""
    env = Env(defs, budget=budget, integer_only=True)

    def lookup(name: str, depth: int) -> Number:
        if not defs.defined(name):
            return 0
        v = env.value(name, depth)
        if isinstance(v, str):
            raise ExprError(f"{name} is a string")
        return v

    try:
        v = cexpr.evaluate(expr, lookup, defined=defs.defined, budget=budget, integer_only=True)
    except ExprError as e:
        raise InputError(where, f"#if {_short(expr)}: {e}") from None
    if isinstance(v, float):
        raise InputError(where, f"#if {_short(expr)}: needs an integer expression")
    return v != 0


def _short(text: str, limit: int = 40) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "..."


def _define(body: str, name: str, params: Optional[str], defs: Defines, where: str) -> None:
    if params is not None:
        if params.replace(" ", "") == "(X)":  # the X-macro tables (MOTOR_FW_ID_TABLE_A)
            new_x: Optional[list[str]] = _x_entries(body, name, where)
        else:
            new_x = None
        if defs.defined(name):
            same = (name in defs.xtables and defs.xtables[name] == new_x) or (name in defs.funcs and new_x is None)
            if not same:
                raise InputError(name, f"redefined at {where} (first defined at {defs.origin.get(name, '?')})")
            return
        if new_x is not None:
            defs.xtables[name] = new_x
        else:
            defs.funcs.add(name)
        defs.origin[name] = where
        return
    body = body.strip()
    if defs.defined(name):
        # C allows a redefinition only with the same replacement list (white space aside)
        if name not in defs.raw or defs.raw[name].split() != body.split():
            raise InputError(name, f"redefined with another value at {where} (first defined at "
                                   f"{defs.origin.get(name, '?')})")
        return
    defs.raw[name] = body
    defs.origin[name] = where


def read_into(defs: Defines, path: str, label: str, budget: cexpr.Budget, profile: bool = False) -> None:
    """Adds what `path` defines to defs, honouring its conditionals (see the module doc).
    A motor profile (`profile`) may not #include: the build would read that file and the
    tool would not, so --check would judge values the build does not use."""
    text = read_text(path, label)
    stack: list[_Cond] = []
    for lineno, line in logical_lines(text, label):
        m = _DIRECTIVE_RE.match(line)
        if m is None:
            continue  # C code, not a directive: nothing to read
        word, rest = m.group(1) or "", m.group(2).strip()
        where = f"{label}:{lineno}"
        on = stack[-1].on if stack else True
        if word in ("if", "ifdef", "ifndef"):
            if len(stack) >= MAX_IF_NESTING:
                raise InputError(where, f"conditionals nested more than {MAX_IF_NESTING} deep")
            cond = False
            if on:
                if word == "if":
                    cond = _pp_condition(rest, defs, where, budget)
                else:
                    mm = _IDENT_ONLY_RE.match(rest)
                    if mm is None:
                        raise InputError(where, f"#{word} needs one macro name")
                    cond = defs.defined(mm.group(1)) == (word == "ifdef")
            stack.append(_Cond(on, cond, where))
        elif word == "elif":
            if not stack or stack[-1].in_else:
                raise InputError(where, "#elif without #if" if not stack else "#elif after #else")
            c = stack[-1]
            c.on = c.parent_on and not c.taken and _pp_condition(rest, defs, where, budget)
            c.taken = c.taken or c.on
        elif word == "else":
            if not stack or stack[-1].in_else:
                raise InputError(where, "#else without #if" if not stack else "a second #else")
            c = stack[-1]
            c.on, c.in_else = c.parent_on and not c.taken, True
            c.taken = True
        elif word == "endif":
            if not stack:
                raise InputError(where, "#endif without #if")
            stack.pop()
        elif not on:
            continue  # C skips every other directive in a group that is not read
        elif word == "define":
            dm = _DEFINE_RE.match(rest)
            if dm is None:
                raise InputError(where, f"#define needs a macro name, found {_short(rest)!r}")
            _define(dm.group(3) or "", dm.group(1), dm.group(2), defs, where)
        elif word == "undef":
            mm = _IDENT_ONLY_RE.match(rest)
            if mm is None:
                raise InputError(where, "#undef needs one macro name")
            defs.undef(mm.group(1))
        elif word == "include" and profile:
            raise InputError(where, f"#include {_short(rest)}: a motor profile holds its own values (the build "
                                    f"would read the included file, tools/tune does not)")
        elif word in ("include", "pragma", "warning", "line", "ident", ""):
            # #include (UserParms.h's of the board and the profile): the caller reads them,
            # in the build's order, never by following a path a header names.
            continue
        elif word == "error":
            raise InputError(where, f"#error {_short(rest)}")
        else:
            raise InputError(where, f"#{_short(word, 20)}: a preprocessor directive tools/tune does not read")
    if stack:
        raise InputError(stack[-1].where, "#if without #endif")


def read_headers(paths: list[str], predefined: Optional[dict[str, str]] = None,
                 profile: Optional[str] = None) -> Defines:
    """Defines of `paths` read in order (one macro table, as one translation unit sees
    them), after `predefined` (the -D options of the build); `profile`, one of the paths,
    is a motor profile (read_into)."""
    defs = Defines()
    for name, body in (predefined or {}).items():
        defs.raw[name] = body
        defs.origin[name] = "<command line>"
    budget = cexpr.Budget()
    for p in paths:
        read_into(defs, p, label(p), budget, profile=p == profile)
    return defs


def label(path: str) -> str:
    """A file's name in messages: relative to the repository when inside it."""
    a = os.path.abspath(path)
    return os.path.relpath(a, REPO) if a.startswith(REPO + os.sep) else path


def read_defines(paths: list[str]) -> tuple[dict[str, str], dict[str, list[str]]]:
    """{name: body text} of the object-like macros and {name: [entries]} of the X-macros."""
    defs = read_headers(paths)
    return defs.raw, defs.xtables


_CSTRING_RE = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
_ESCAPES = {"n": "\n", "t": "\t", "\\": "\\", '"': '"', "'": "'", "?": "?", "a": "\a", "b": "\b", "f": "\f",
            "r": "\r", "v": "\v"}


def _c_string(body: str, name: str) -> str:
    m = _CSTRING_RE.fullmatch(body)
    if m is None:
        raise InputError(name, f"{_short(body)!r} is not one string literal")
    out: list[str] = []
    s = m.group(1)
    i = 0
    while i < len(s):
        c = s[i]
        if c == "\\":
            e = s[i + 1]
            if e not in _ESCAPES:
                raise InputError(name, f"escape \\{e} in a string is not supported")
            out.append(_ESCAPES[e])
            i += 2
        else:
            out.append(c)
            i += 1
    return "".join(out)


class Env:
    """Evaluates macro values as numbers (or strings) on demand, through cexpr. Each value
    is computed once (cached); a macro met again while its own value is being computed
    is a cycle and refused."""

    def __init__(self, defs: Defines, budget: Optional[cexpr.Budget] = None, integer_only: bool = False):
        self.defs, self.integer_only = defs, integer_only
        self.raw, self.xtables = defs.raw, defs.xtables
        self.cache: dict[str, Value] = {}
        self.budget = budget if budget is not None else cexpr.Budget()
        self._active: list[str] = []

    def has(self, name: str) -> bool:
        return name in self.raw

    def where(self, name: str) -> str:
        return self.defs.origin.get(name, "?")

    def get(self, name: str) -> Value:
        """The value of a macro: int, float or str. InputError naming it when it is missing
        or cannot be computed."""
        return self.value(name, 0)

    def number(self, name: str) -> Number:
        """A macro that must be a number, int or float as C types it (finite: cexpr
        refuses anything else)."""
        v = self.get(name)
        if isinstance(v, str):
            raise InputError(name, f"is the string {v[:40]!r}; a number is needed ({self.where(name)})")
        return v

    def num(self, name: str) -> float:
        return float(self.number(name))

    def value(self, name: str, depth: int) -> Value:
        if name in self.cache:
            return self.cache[name]
        if name not in self.raw:
            if name in self.xtables or name in self.defs.funcs:
                raise InputError(name, f"is a function-like macro ({self.where(name)}); a value is needed")
            if self._active:
                raise InputError(self._active[-1], f"uses {name}, which is not defined "
                                                   f"({self.where(self._active[-1])})")
            raise InputError(name, "missing (the core needs it)")
        if name in self._active:
            chain = " -> ".join(self._active[self._active.index(name):] + [name])
            raise InputError(name, f"defined in terms of itself ({chain})")
        body = self.raw[name]
        self._active.append(name)
        try:
            val: Value
            if body.startswith('"'):
                val = _c_string(body, name)
            else:
                val = cexpr.evaluate(body, self._lookup, depth, budget=self.budget, integer_only=self.integer_only)
        except ExprError as e:
            raise InputError(name, f"{e} ({self.where(name)})") from None
        finally:
            self._active.pop()
        self.cache[name] = val
        return val

    def _lookup(self, name: str, depth: int) -> Number:
        v = self.value(name, depth)
        if isinstance(v, str):
            raise ExprError(f"{name} is a string, not a number")
        return v

    def expression(self, expr: str) -> Number:
        """A C expression over the macros (the X-macro table's entries)."""
        return cexpr.evaluate(expr, self._lookup, budget=self.budget)

    def table(self, name: str) -> list[float]:
        out = []
        for a in self.xtables[name]:
            try:
                out.append(float(self.expression(a)))
            except ExprError as e:
                raise InputError(name, f"entry {_short(a)!r}: {e} ({self.where(name)})") from None
        return out


def board_name_ok(board: str) -> str:
    if not isinstance(board, str) or not NAME_RE.fullmatch(board):
        raise InputError("board", f"{str(board)[:40]!r}: a board name is lower-case letters, digits and _")
    return board


def _board_header(board: str) -> str:
    """boards/board_<board>.h, or InputError naming the boards there are."""
    board_h = os.path.join(REPO, "boards", f"board_{board_name_ok(board)}.h")
    if not os.path.isfile(board_h):
        have = sorted(f[6:-2] for f in os.listdir(os.path.join(REPO, "boards")) if f.startswith("board_"))
        raise InputError("board", f"no boards/board_{board}.h (boards: {', '.join(have)})")
    return board_h


def profile_env(motor_header: str, board: str) -> Env:
    """Env of a motor header as built with BOARD=board: the board, the motor, UserParms.h,
    with the -D options the build passes (MC_BOARD_<BOARD>, MC_MOTOR_HEADER)."""
    board_h = _board_header(board)
    # UserParms.h includes boards/board.h (the board profile, then the PWM
    # settings the HAL reads too), then the motor; a motor profile cannot
    # move the PWM, only check it (emit.py).
    pre = {f"MC_BOARD_{board.upper()}": "1", "MC_MOTOR_HEADER": '"motor.h"'}
    return Env(read_headers([board_h, BOARD_H, motor_header, os.path.join(FIRMWARE, "UserParms.h")], pre,
                            profile=motor_header))


def board_env(board: str) -> Env:
    """Env of a board with UserParms.h's defaults (no motor)."""
    pre = {f"MC_BOARD_{board_name_ok(board).upper()}": "1"}
    return Env(read_headers([_board_header(board), BOARD_H, os.path.join(FIRMWARE, "UserParms.h")], pre))


# ---- the core's arithmetic --------------------------------------------------


def duty_sample_max(fcy: float, fpwm: float, trig_tcy: float, deadtime_ns: float, min_on_ns: float) -> float:
    """mc_derived.h MC_DUTY_SAMPLE_MAX: the largest duty (counts) of a measured
    phase that leaves its low-side switch on min_on_ns before the ADC trigger,
    trig_tcy after the centre-aligned period's midpoint, and still on at it.
    Truncated toward zero like the core's (int16_t); a header's 1e308 gives -inf
    (which its range check then refuses), never an exception."""
    ptper = fcy // fpwm / 2.0 - 1.0
    dt = deadtime_ns * 1e-9 * fcy
    on = min_on_ns * 1e-9 * fcy
    win = min(2.0 * (ptper - trig_tcy) - 2.0, 2.0 * (ptper + trig_tcy - dt - on))
    return float(math.trunc(win)) if math.isfinite(win) else -math.inf


def q15_round(x: float) -> int:
    """q15.h Q15(x): range [-1, 1], x*32768 rounded half away from zero, 1.0 -> 32767."""
    if not (-1.0 <= x <= 1.0):
        raise ValueError(f"Q15({x!r}) out of [-1, 1]")
    if x * 32768.0 >= 32767.5:
        return 32767
    return int(x * 32768.0 + (0.5 if x >= 0 else -0.5))


def shift_of(x: float, top: int = 7) -> int:
    s = 0
    while s < top and x >= float(1 << s):
        s += 1
    return s


def mant_shift(x: float, top: int = 7) -> tuple[int, int]:
    s = shift_of(x, top)
    return q15_round(x / float(1 << s)), s


def _expneg(y: float) -> float:
    # SMC_EXPNEG_ of smc.h: the (3,3) Pade approximant of exp(-y).
    return (1.0 - y * (0.5 - y * (0.1 - y / 120.0))) / (1.0 + y * (0.5 + y * (0.1 + y / 120.0)))


class Derived:
    """Rows (name, engineering value, unit, Q15 integer or None, decoded value,
    note) and failed checks (parameter, message)."""

    def __init__(self) -> None:
        self.rows: list[tuple[str, float, str, Optional[int], Optional[float], str]] = []
        self.failures: list[tuple[str, str]] = []

    def row(self, name: str, eng: float, unit: str, q: Optional[int] = None, decoded: Optional[float] = None,
            note: str = "") -> None:
        self.rows.append((name, eng, unit, q, decoded, note))

    def check(self, param: str, cond: bool, msg: str) -> bool:
        if not cond:
            self.failures.append((param, msg))
        return cond


def scale_value(env: Env, name: str, why: str, whole: bool = False, hi: float = math.inf) -> Number:
    """A value every other one is divided by or scaled with: without it nothing can be
    computed, so a bad one is an InputError (one line) rather than a failed check."""
    v = env.number(name)
    if not 0 < v <= hi or (whole and v != int(v)):
        kind = "a whole number" if whole else "a number"
        rng = f"in 1..{hi:g}" if hi != math.inf else "> 0"
        raise InputError(name, f"{v!r}: must be {kind} {rng} ({why}; {env.where(name)})")
    return v


def derive_core(env: Env) -> Derived:
    """Replays mc_derived.h / SMC_PARAMS_INIT / mc.c for the macros in env. A macro that
    is missing or not a number, or a scale that makes the rest meaningless (a zero the
    core divides by), raises InputError naming it; every other problem is a failed check."""
    d = Derived()

    g = env.number

    fcy = scale_value(env, "BOARD_FCY_HZ", "the instruction clock", whole=True)
    fpwm = scale_value(env, "PWM_FREQUENCY_HZ", "the PWM and current-loop rate")
    i_fs = scale_value(env, "BOARD_I_FULLSCALE_A", "the current scale; mc_derived.h")
    vbus_fs = scale_value(env, "BOARD_VBUS_FULLSCALE_V", "the bus-voltage scale; mc_derived.h")
    vbus_nom = scale_value(env, "BOARD_VBUS_NOMINAL_V", "the voltage scale is BOARD_VBUS_NOMINAL_V / sqrt 3")
    loop_hz = scale_value(env, "MC_SPEED_LOOP_HZ", "the speed-loop rate; mc_derived.h")
    pp = scale_value(env, "MOTOR_POLE_PAIRS", "mc_derived.h", whole=True, hi=32)
    fs_rpm = scale_value(env, "MC_SPEED_FULLSCALE_RPM", "the speed scale; mc_derived.h")
    if fpwm // loop_hz < 1:
        raise InputError("MC_SPEED_LOOP_HZ", f"{loop_hz!r}: must not exceed PWM_FREQUENCY_HZ {fpwm!r} "
                         f"(IRP_PERCALC = PWM periods per speed-loop run >= 1; {env.where('MC_SPEED_LOOP_HZ')})")
    ts = 1.0 / fpwm
    v_fs = vbus_nom / SQRT3
    w_fs = fs_rpm * pp / 60.0

    # timing
    d.check("PWM_FREQUENCY_HZ", 4000 <= fpwm <= 40000, "must be in 4000..40000 Hz")
    d.check("PWM_FREQUENCY_HZ", fcy % fpwm == 0, "BOARD_FCY_HZ / PWM_FREQUENCY_HZ must be an integer")
    duty_max = fcy // fpwm
    d.check("PWM_FREQUENCY_HZ", duty_max <= 32767, "duty full scale must be <= 32767 counts")
    d.check("MC_SPEED_LOOP_HZ", loop_hz > 0 and fpwm % loop_hz == 0, "must divide PWM_FREQUENCY_HZ")
    irp = fpwm // loop_hz
    d.check("MC_SPEED_LOOP_HZ", 1 <= irp <= 256, "IRP_PERCALC must be in 1..256")
    d.row("PWM_DUTY_MAX", duty_max, "counts", note="BOARD_FCY_HZ / PWM_FREQUENCY_HZ")
    d.row("IRP_PERCALC", irp, "periods", note="PWM periods per speed-loop run")
    d.row("scale: current", i_fs, "A", note="Q15 full scale (BOARD_I_FULLSCALE_A)")
    d.row("scale: voltage", v_fs, "V", note="Q15 full scale, BOARD_VBUS_NOMINAL_V / sqrt 3")
    d.row("scale: speed", fs_rpm, "rpm", note="Q15 full scale (MC_SPEED_FULLSCALE_RPM)")

    def q_scaled(name: str, x: float, fs: float, unit: str, scale: str, note: str) -> None:
        """A row for x as Q15 of the full scale fs (checked, then saturated like Q15())."""
        d.check(name, -1.0 <= x / fs <= 1.0, f"out of the {scale} Q15 range")
        q = q15_round(max(-1.0, min(1.0, x / fs)))
        d.row(name, x, unit, q, q / 32768.0 * fs, note)

    def q_rpm(name: str, rpm: float, note: str = "") -> None:
        q_scaled(name, rpm, fs_rpm, "rpm", "speed", note)

    def q_amp(name: str, a: float, note: str = "") -> None:
        q_scaled(name, a, i_fs, "A", "current", note)

    # speeds
    n_min, n_nom, n_fw = g("MOTOR_SPEED_MIN_RPM"), g("MOTOR_SPEED_NOMINAL_RPM"), g("MOTOR_SPEED_FW_MAX_RPM")
    ref_min, ref_max = g("SPEED_REF_MIN_RPM"), g("SPEED_REF_MAX_RPM")
    ramp_end, est_min = g("MOTOR_RAMP_END_RPM"), g("MC_ESTIMATOR_MIN_RPM")
    d.check("MOTOR_SPEED_MIN_RPM", 0.0 < n_min < n_nom, "must be in (0, MOTOR_SPEED_NOMINAL_RPM)")
    d.check("MOTOR_SPEED_FW_MAX_RPM", n_fw >= n_nom, "must be >= MOTOR_SPEED_NOMINAL_RPM")
    d.check("MC_SPEED_FULLSCALE_RPM", n_fw <= 0.95 * fs_rpm, "must be >= MOTOR_SPEED_FW_MAX_RPM / 0.95")
    d.check("SPEED_REF_MIN_RPM", 0.0 < ref_min < ref_max, "must be in (0, SPEED_REF_MAX_RPM)")
    d.check("SPEED_REF_MAX_RPM", ref_max <= n_fw, "must be <= MOTOR_SPEED_FW_MAX_RPM")
    d.check("MC_ESTIMATOR_MIN_RPM", 0.0 < est_min <= ramp_end, "must be in (0, MOTOR_RAMP_END_RPM]")
    q_rpm("SPEED_REF_MIN_RPM", ref_min, "pot at 0")
    q_rpm("SPEED_REF_MAX_RPM", ref_max, "pot at full travel")
    q_rpm("MOTOR_SPEED_NOMINAL_RPM", n_nom, "field weakening starts above")
    q_rpm("MOTOR_SPEED_FW_MAX_RPM", n_fw, "top of the field-weakening table")
    step = g("MC_SPEED_RAMP_RPM_PER_S") / loop_hz / fs_rpm * 32768.0
    if d.check("MC_SPEED_RAMP_RPM_PER_S", 1.0 <= step < 32767.0, "must give 1..32767 Q15 counts per speed-loop run"):
        step_q = int(step + 0.5)
        d.row("MC_SPEED_RAMP_STEP", g("MC_SPEED_RAMP_RPM_PER_S"), "rpm/s", step_q,
              step_q / 32768.0 * fs_rpm * loop_hz, "speed-reference slew, counts per speed-loop run")

    # currents
    i_max, trip = g("MOTOR_CURRENT_MAX_A"), g("MC_OVERCURRENT_A")
    i_lock, i_ramp, off_max = g("MOTOR_LOCK_CURRENT_A"), g("MOTOR_RAMP_CURRENT_A"), g("MC_OFFSET_MAX_A")
    d.check("MOTOR_CURRENT_MAX_A", 0.0 < i_max < i_fs, "must be in (0, BOARD_I_FULLSCALE_A)")
    d.check("MC_OVERCURRENT_A", i_max < trip < i_fs, "must be in (MOTOR_CURRENT_MAX_A, BOARD_I_FULLSCALE_A)")
    d.check("MOTOR_LOCK_CURRENT_A", 0.0 < i_lock < trip, "must be in (0, MC_OVERCURRENT_A)")
    d.check("MOTOR_RAMP_CURRENT_A", 0.0 < i_ramp <= i_max, "must be in (0, MOTOR_CURRENT_MAX_A]")
    d.check("MC_OFFSET_MAX_A", 0.0 < off_max < i_fs, "must be in (0, BOARD_I_FULLSCALE_A)")
    q_amp("MOTOR_CURRENT_MAX_A", i_max, "|Iq| limit of the speed loop")
    q_amp("MC_OVERCURRENT_A", trip, "software trip, any phase")
    q_amp("total |I| limit in FW", 0.9 * trip, "mc.c MC_I_TOTAL: 90 % of the trip")
    q_amp("MOTOR_LOCK_CURRENT_A", i_lock, "Iq during the lock")
    if env.has("MC_DEADTIME_MEASURE") and g("MC_DEADTIME_MEASURE") != 0 and env.has("MC_DEADTIME_BAND_A"):
        # mc.c note 4: the lock's dead-time measurement needs 1.5 bands at 3/4 of the lock current
        # in phases B and C (cos 30 deg): MC_CHECK_FOR(MOTOR_LOCK_CURRENT_A, MC_DEADTIME_BAND_A)
        band = g("MC_DEADTIME_BAND_A")
        d.check("MOTOR_LOCK_CURRENT_A", i_lock >= 1.5 * band / (0.75 * SQRT3 / 2.0),
                f"must be at least 2.31 dead-time bands (MC_DEADTIME_BAND_A = {band:.4g} A) to measure the dead "
                f"time at the lock (mc.c note 4)")
    q_amp("MOTOR_RAMP_CURRENT_A", i_ramp, "Iq during the open-loop ramp")
    damp, damp_max = g("MOTOR_OL_DAMP_S"), g("MC_OL_DAMP_MAX_DEG")
    # mc_derived.h MC_CHECK(MOTOR_OL_DAMP_S): 0 (off) or one Q4 count (1/16 period) .. 1000 periods
    if d.check("MOTOR_OL_DAMP_S", 0.0 <= damp and damp * fpwm <= 1000.0 and (damp == 0.0 or damp * fpwm * 16.0 >= 0.5),
               "must be 0 (off) or 1/16..1000 PWM periods"):
        d.row("MOTOR_OL_DAMP_S", damp, "s", int(damp * fpwm * 16.0 + 0.5), None,
              "open-loop damping, MC_OL_DAMP_K (Q4 periods)")
    d.check("MC_OL_DAMP_MAX_DEG", 0.0 <= damp_max <= 90.0, "must be 0..90 deg")

    # bus
    uv, ov = g("MC_VBUS_UNDERVOLTAGE_V"), g("MC_VBUS_OVERVOLTAGE_V")
    d.check("MC_VBUS_UNDERVOLTAGE_V", 0.0 < uv < vbus_nom, "must be in (0, BOARD_VBUS_NOMINAL_V)")
    d.check("MC_VBUS_OVERVOLTAGE_V", vbus_nom < ov < vbus_fs, "must be in (BOARD_VBUS_NOMINAL_V, BOARD_VBUS_FULLSCALE_V)")
    vlim = g("MC_VOLTAGE_LIMIT_FRACTION")
    if d.check("MC_VOLTAGE_LIMIT_FRACTION", 0.5 < vlim <= 1.0, "must be in (0.5, 1]"):
        q = q15_round(vlim)
        d.row("MC_VOLTAGE_LIMIT_FRACTION", vlim * v_fs, "V", q, q / 32768.0 * v_fs, "largest |V|, phase peak")

    def gain_kept(name: str, value: float, q: int, what: str, hint: str) -> None:
        """A gain whose Q15 integer is 0 does nothing in the core, whatever the header says;
        the usual cause is a unit slip upstream (an inertia in g cm^2 written as kg m^2)."""
        d.check(name, q != 0, f"{value:g} rounds to 0 in Q15: the {what} would do nothing ({hint})")

    # current PI
    kp, ki = g("MOTOR_CURRENT_KP_V_PER_A"), g("MOTOR_CURRENT_KI_V_PER_AS")
    kp_ = kp * i_fs / v_fs
    ki_ = ki * ts * i_fs / v_fs
    if d.check("MOTOR_CURRENT_KP_V_PER_A", 0.0 <= kp_ < 128.0, "Kp * I_FS / V_FS must be in [0, 128)"):
        m, s = mant_shift(kp_)
        d.row("MOTOR_CURRENT_KP_V_PER_A", kp, "V/A", m, m * (1 << s) / 32768.0 * v_fs / i_fs, f"MC_CUR_KP, shift {s}")
        gain_kept("MOTOR_CURRENT_KP_V_PER_A", kp, m, "current loops' proportional gain", "L too small, or its unit?")
    if d.check("MOTOR_CURRENT_KI_V_PER_AS", 0.0 <= ki_ < 1.0, "Ki * Ts * I_FS / V_FS must be in [0, 1)"):
        q = q15_round(ki_)
        d.row("MOTOR_CURRENT_KI_V_PER_AS", ki, "V/(A s)", q, q / 32768.0 * v_fs / i_fs / ts, "MC_CUR_KI, per period")
        gain_kept("MOTOR_CURRENT_KI_V_PER_AS", ki, q, "current loops' integral gain", "R too small, or its unit?")
    # speed PI
    kp, ki = g("MOTOR_SPEED_KP_A_PER_RPM"), g("MOTOR_SPEED_KI_A_PER_RPM_S")
    kp_ = kp * fs_rpm / i_fs
    ki_ = ki / loop_hz * fs_rpm / i_fs
    if d.check("MOTOR_SPEED_KP_A_PER_RPM", 0.0 <= kp_ < 128.0, "Kp * speed FS / I_FS must be in [0, 128)"):
        m, s = mant_shift(kp_)
        d.row("MOTOR_SPEED_KP_A_PER_RPM", kp, "A/rpm", m, m * (1 << s) / 32768.0 * i_fs / fs_rpm, f"MC_SPD_KP, shift {s}")
        gain_kept("MOTOR_SPEED_KP_A_PER_RPM", kp, m, "speed loop's proportional gain", "the inertia's unit?")
    if d.check("MOTOR_SPEED_KI_A_PER_RPM_S", 0.0 <= ki_ < 1.0, "Ki / loop rate * speed FS / I_FS must be in [0, 1)"):
        q = q15_round(ki_)
        d.row("MOTOR_SPEED_KI_A_PER_RPM_S", ki, "A/(rpm s)", q, q / 32768.0 * i_fs / fs_rpm * loop_hz, "MC_SPD_KI, per speed-loop run")
        gain_kept("MOTOR_SPEED_KI_A_PER_RPM_S", ki, q, "speed loop's integral gain", "the inertia's unit?")

    if env.has("MOTOR_SPEED_KP_FULL_RPM"):  # the core's Kp gain schedule (mc.c)
        n_kp = g("MOTOR_SPEED_KP_FULL_RPM")
        if d.check("MOTOR_SPEED_KP_FULL_RPM", 0.0 < n_kp <= n_fw, "must be in (0, MOTOR_SPEED_FW_MAX_RPM]"):
            q_rpm("MOTOR_SPEED_KP_FULL_RPM", n_kp, "speed-PI Kp full above, scaled down below")
    if env.has("MC_SPEED_KP_MIN_FRACTION"):
        fr = g("MC_SPEED_KP_MIN_FRACTION")
        if d.check("MC_SPEED_KP_MIN_FRACTION", 0.0 < fr <= 1.0, "must be in (0, 1]"):
            q = q15_round(fr)
            d.row("MC_SPEED_KP_MIN_FRACTION", fr, "", q, q / 32768.0, "smallest scheduled Kp fraction")

    # start-up
    t_lock = g("MOTOR_LOCK_TIME_S")
    if d.check("MOTOR_LOCK_TIME_S", 1.0 <= t_lock * fpwm <= 65000.0, "must be 1..65000 PWM periods"):
        lp = int(t_lock * fpwm + 0.5)
        d.row("MOTOR_LOCK_TIME_S", t_lock, "s", lp, lp * ts, "MC_LOCK_PERIODS (periods)")
    t_ramp = g("MOTOR_RAMP_TIME_S")
    periods = t_ramp * fpwm
    inc_ = ramp_end * pp / 60.0 * ts * 4294967296.0 / periods if periods > 0 else 0.0
    d.check("MOTOR_RAMP_END_RPM", est_min <= ramp_end < n_nom, "must be in [MC_ESTIMATOR_MIN_RPM, MOTOR_SPEED_NOMINAL_RPM)")
    ok = d.check("MOTOR_RAMP_TIME_S", 100.0 <= periods <= 4.0e6, "must be 100..4e6 PWM periods")
    ok = d.check("MOTOR_RAMP_TIME_S", inc_ >= 8.0, "ramp too slow for the 32-bit angle (step increment < 8)") and ok
    # the step is added to a 32-bit angle step every period: beyond 2^32 it has no meaning
    ok = d.check("MOTOR_RAMP_END_RPM", inc_ < 4294967296.0, "ramp too fast for the 32-bit angle step") and ok
    if ok:
        inc = int(inc_ + 0.5)
        end = inc * int(periods + 0.5)
        d.row("MOTOR_RAMP_TIME_S", t_ramp, "s", int(periods + 0.5), int(periods + 0.5) * ts, "ramp periods")
        d.row("MOTOR_RAMP_END_RPM", ramp_end, "rpm", end, end * fpwm * 60.0 / (4294967296.0 * pp),
              "MC_RAMP_STEP_END (32-bit angle step)")
        accel = inc * fpwm * fpwm * 60.0 / (4294967296.0 * pp)
        d.row("ramp acceleration", ramp_end / t_ramp if t_ramp else 0.0, "rpm/s", inc, accel,
              "MC_RAMP_STEP_INC per period")

    # estimator (SMC_PARAMS_INIT)
    r, l, ke = g("MOTOR_RS_OHM"), g("MOTOR_LS_H"), g("MOTOR_KE_VPK_LL_PER_KRPM")
    kslide_v, band_a = g("MOTOR_SMC_GAIN_V"), g("MOTOR_SMC_LINEAR_BAND_A")
    spd_fc = g("MC_SPEED_FILTER_HZ")
    d.check("MOTOR_RS_OHM", r > 0.0, "must be > 0")
    d.check("MOTOR_LS_H", l > 0.0, "must be > 0")
    d.check("MOTOR_KE_VPK_LL_PER_KRPM", ke > 0.0, "must be > 0")
    if r <= 0.0 or l <= 0.0:
        return d
    y = ts * r / l
    d.check("MOTOR_LS_H", y < 1.0, "F = 1 - Ts R / L must be > 0 (L too small for MOTOR_RS_OHM)")
    d.check("MOTOR_LS_H", ts / l * v_fs / i_fs < 1.0, "G = Ts/L * V_FS/I_FS must be < 1")
    e_ratio = 2.0  # smc.h SMC_EMF_FS_RATIO: back-EMF scale E_FS = 2 V_FS
    d.check("MOTOR_SMC_GAIN_V", 0.0 < kslide_v < e_ratio * v_fs, "Kslide must be in (0, 2 V_FS = 2 BOARD_VBUS_NOMINAL_V / sqrt 3)")
    d.check("MOTOR_SMC_LINEAR_BAND_A", i_fs / 32768.0 < band_a < i_fs, "must be in (1 LSB, BOARD_I_FULLSCALE_A)")
    d.check("MC_SPEED_FILTER_HZ", 0.0 < TWO_PI * spd_fc / loop_hz < 1.0, "2 pi fc / MC_SPEED_LOOP_HZ must be in (0, 1)")
    if not y < 1.0:
        return d
    f = _expneg(y)
    gg = (1.0 - f) / r * v_fs / i_fs  # G in V_FS units
    ge = gg * e_ratio  # ... and in the core's E_FS units
    ks = kslide_v / v_fs
    me = band_a / i_fs
    kz = ks / e_ratio / me if me > 0.0 else math.inf
    d.row("F (AN1078 Eq. 2: 1 - Ts R/L)", 1.0 - y, "", None, None, "the Euler form of AN1078")
    q = q15_round(f)
    d.row("smc F = exp(-Ts R/L)", f, "", q, q / 32768.0, "the core's exact discretisation (Pade 3,3)")
    d.row("G (AN1078 Eq. 2: Ts/L)", ts / l, "A/(V period)", None, None, "in amps per volt")
    d.row("G = (1-F)/R * V_FS/I_FS", gg, "I_FS/V_FS", None, None, "in the core's current and voltage scales")
    if d.check("smc_G", 1e-4 <= ge < 128.0, "G * 2 V_FS / I_FS must be in [1e-4, 128)"):
        m, s_ = mant_shift(ge, 7)
        d.row("smc G = (1-F)/R * 2V_FS/I_FS", ge, "I_FS/E_FS", m, m * (1 << s_) / 32768.0, f"g_shift {s_}")
    if d.check("MOTOR_SMC_GAIN_V", 0.0 < ks < e_ratio, "smc: Kslide must be in (0, 2) of V_FS"):
        q = q15_round(ks / e_ratio)
        d.row("MOTOR_SMC_GAIN_V", kslide_v, "V", q, q / 32768.0 * v_fs * e_ratio, "Kslide, Q15 of E_FS = 2 V_FS")
    if d.check("MOTOR_SMC_LINEAR_BAND_A", 1.0 / 32768.0 <= me < 1.0, "smc: MaxSMCError must be in [1 LSB, 1)"):
        q = q15_round(me)
        d.row("MOTOR_SMC_LINEAR_BAND_A", band_a, "A", q, q / 32768.0 * i_fs, "MaxSMCError")
    if d.check("MOTOR_SMC_LINEAR_BAND_A", 0.0 < kz < 32768.0, "smc: Kslide / MaxSMCError must be in (0, 32768)"):
        m, s_ = mant_shift(kz, 15)
        d.row("smc Kz = Kslide / MaxSMCError", kz, "E_FS/I_FS", m, m * (1 << s_) / 32768.0, f"kz_shift {s_}")
    if math.isfinite(kz):
        d.row("smc loop gain c = G Kz", ge * kz, "", None, None,
              "linear band dead-beat at c = F; relay (chattering) mode above 1 + F")
    kpw = TWO_PI * w_fs * ts
    if d.check("MC_SPEED_FULLSCALE_RPM", kpw < 1.0, "smc: 2 pi omega_fs Ts must be below 1"):
        q = q15_round(kpw)
        d.row("smc K per unit speed", kpw, "rad/period", q, q / 32768.0, "Kslf at full-scale speed (AN1078 Eq. 7)")
    f_min = est_min * pp / 60.0
    ok = d.check("MC_ESTIMATOR_MIN_RPM", 0.0 < f_min < w_fs and TWO_PI * f_min * ts >= 1.0 / 32768.0,
                 "smc: min speed must be in (0, omega_fs)")
    if ok and kpw < 1.0:  # below omega_fs, whose own step 2 pi omega_fs Ts is checked above
        q = q15_round(TWO_PI * f_min * ts)
        d.row("smc K floor (filter floor)", est_min, "rpm", q, q / 32768.0 / (TWO_PI * ts) * 60.0 / pp,
              f"Kslf floor 2 pi f_min Ts = {TWO_PI * f_min * ts:.5f} at MC_ESTIMATOR_MIN_RPM")
    kspeed = 1.0 / (2.0 * irp * ts * w_fs)
    d.check("MC_SPEED_FULLSCALE_RPM", kspeed < 32768.0, "smc: speed scale must be below 32768")
    kslpf = TWO_PI * spd_fc * irp * ts
    if d.check("MC_SPEED_FILTER_HZ", 0.0 < kslpf < 1.0, "smc: speed filter coefficient must be in (0, 1)"):
        q = q15_round(kslpf)
        d.row("MC_SPEED_FILTER_HZ", spd_fc, "Hz", q, q / 32768.0 / (TWO_PI * irp * ts), "speed filter")
    # back-EMF consistency gain (note 5 of smc.h): Ke w_fs / E_FS x 0.31
    ke_hz = ke / SQRT3 / (1000.0 * pp / 60.0)
    emfg = ke_hz * w_fs / (v_fs * e_ratio) * 0.31
    d.check("MOTOR_KE_VPK_LL_PER_KRPM", 0.0 <= emfg < 8.0, "smc: Ke omega_fs / E_FS gain must be in [0, 8)")
    # mc.c
    d.check("MC_SPEED_FULLSCALE_RPM", 3.0 * w_fs * ts < 1.0, "3 omega_fs Ts must be < 1 (PWM too slow)")
    # the applied-voltage scale (mc_derived.h MC_VAPP_K_): fewer duty counts, a larger factor
    vapp = SQRT3 / (3.0 * duty_max) * vbus_fs / vbus_nom * 33554432.0 if duty_max > 0 else math.inf
    d.check("PWM_FREQUENCY_HZ", 1024.0 <= vapp < 32767.0,
            "BOARD_VBUS_FULLSCALE_V / BOARD_VBUS_NOMINAL_V / PWM_DUTY_MAX out of the applied-voltage scaling's range")
    # dead time
    dt = g("PWM_DEADTIME_NS") * 1e-9 * fcy
    dt_ok = d.check("PWM_DEADTIME_NS", 0.0 <= dt < 0.1 * duty_max, "must be below 10 % of the PWM period")
    if env.has("MC_DEADTIME_BAND_A"):  # mc_derived.h MC_CHECK_FOR(MC_DEADTIME_BAND_A, MOTOR_LS_H), twice
        band = g("MC_DEADTIME_BAND_A")
        if d.check("MC_DEADTIME_BAND_A", 0.5 <= band / i_fs * 32768.0 and band < 0.25 * i_fs,
                   "must be in [1 Q15 count, BOARD_I_FULLSCALE_A / 4) (the dead-time band, from MOTOR_LS_H)") and dt_ok:
            d.check("MC_DEADTIME_BAND_A", int(dt + 0.5) * 32768.0 / q15_round(band / i_fs) < 32767.0,
                    "too narrow for the dead-time counts (in-band slope >= 1): MOTOR_LS_H too large for the default")
    if env.has("MC_STALL_SPEED_ERROR_RPM"):
        d.check("MC_STALL_SPEED_ERROR_RPM", 0.0 < g("MC_STALL_SPEED_ERROR_RPM") < fs_rpm,
                "must be in (0, MC_SPEED_FULLSCALE_RPM)")
    # shunt window
    trig = g("PWM_ADC_TRIGGER_TCY")
    d.check("PWM_ADC_TRIGGER_TCY", 0.0 <= trig and trig * 2.0 * fpwm < fcy,
            "the trigger must fall in the second half of the period")
    win = duty_sample_max(fcy, fpwm, trig, g("PWM_DEADTIME_NS"), g("BOARD_SHUNT_MIN_ON_NS"))
    d.check("BOARD_SHUNT_MIN_ON_NS", g("BOARD_SHUNT_MIN_ON_NS") >= 0.0 and win >= 0.75 * duty_max,
            "with PWM_ADC_TRIGGER_TCY and PWM_DEADTIME_NS it must leave the measured phases at least 75 % duty")
    d.row("MC_DUTY_SAMPLE_MAX", win, "counts", note="largest duty of a measured phase (shunt window)")
    # field weakening
    if "MOTOR_FW_ID_TABLE_A" in env.xtables:
        tab = env.table("MOTOR_FW_ID_TABLE_A")
        d.check("MOTOR_FW_ID_TABLE_A", len(tab) == 16, "must have exactly 16 entries")
        d.check("MOTOR_FW_ID_TABLE_A", all(-i_fs < a <= 0.0 for a in tab),
                "every entry must be in (-BOARD_I_FULLSCALE_A, 0] amps")
        for k, a in enumerate(tab):
            n = n_nom + (n_fw - n_nom) * k / 15.0
            q = q15_round(max(-1.0, min(1.0, a / i_fs)))
            d.row(f"FW Id[{k:2d}] at {n:7.0f} rpm", a, "A", q, q / 32768.0 * i_fs)
    else:
        d.check("MOTOR_FW_ID_TABLE_A", False, "missing (16-entry X-macro table)")
    return d


def format_table(d: Derived, title: str) -> str:
    out = [title, f"{'quantity':34s} {'value':>12s} {'unit':10s} {'Q15/int':>10s} {'decoded':>12s}  note"]
    for name, eng, unit, q, dec, note in d.rows:
        ev = f"{eng:12.6g}" if isinstance(eng, (int, float)) else f"{str(eng):>12s}"
        qs = f"{q:10d}" if q is not None else f"{'':10s}"
        ds = f"{dec:12.6g}" if dec is not None else f"{'':12s}"
        out.append(f"{name:34s} {ev} {unit:10s} {qs} {ds}  {note}".rstrip())
    if d.failures:
        out.append("")
        for p, m in d.failures:
            out.append(f"CHECK FAILED  {p}: {m}")
    else:
        out.append("every check of mc_derived.h / smc.h / mc.c passes")
    return "\n".join(out)
