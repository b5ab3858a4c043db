"""A small evaluator for the C constant expressions of the firmware's headers.

The values of firmware/motors/*.h, boards/*.h and firmware/UserParms.h
are numbers, other macros and a little arithmetic on them:

    20000L   4.4   7.5e-06   (-1)   (0.8 * MOTOR_RAMP_END_RPM)
    ((double)BOARD_VBUS_NOMINAL_V / (12.0 * (double)MOTOR_LS_H * (double)PWM_FREQUENCY_HZ))
    ((4.0 * MC_DEADTIME_BAND_A < 0.4 * MOTOR_CURRENT_MAX_A) ? 4.0 * MC_DEADTIME_BAND_A : 0.4 * MOTOR_CURRENT_MAX_A)

This module accepts exactly that kind of text and nothing else: C integer and
floating literals (with their suffixes), names that the caller resolves (the
macro table), parentheses, casts to signed arithmetic types, unary + - !,
binary * / % + -, the comparisons, && || and ?: (whose result takes C's usual
arithmetic conversions: `(1 ? 3 : 2.0) / 2` is 1.5). Anything else (strings,
member access, calls, indexing, Python's **, the bitwise operators no header
uses) is refused with one line saying what and where, and so are unsigned
constants and casts (`1u < -1` is 1 in C: the -1 converts to unsigned, at 16
bits on the dsPIC and 32 on the host; no header the tool reads has one). In
an #if (integer_only) a floating constant or a cast is refused, as the C
preprocessor refuses it. A header is data, never code: it used to go to
Python's eval, which ran what a header put there.

The work is bounded: MAX_TOKENS tokens per expression, MAX_NESTING levels of
parentheses, unary operators, ?: and macro expansion together (one counter,
so a chain of macros cannot multiply it), and every integer stays within 64
bits (what a C compiler could hold), every float finite.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Callable, Optional, Union

Number = Union[int, float]

MAX_TOKENS = 2000  # the longest value in the shipped headers (MC_ID_MIN_A) has 21
MAX_NESTING = 32  # parentheses + unary operators + ?: + macro expansions, together
MAX_LITERAL = 64  # characters of one number literal
INT_LIMIT = 1 << 64  # |integer| must stay below this: C's widest type (unsigned long long)


class ExprError(Exception):
    """An expression this evaluator refuses; the message is one line that says why."""


@dataclass
class Budget:
    """Tokens left for a whole read (a header's #if lines share one): bounds the total work."""

    tokens: int = 1_000_000

    def spend(self, n: int) -> None:
        self.tokens -= n
        if self.tokens < 0:
            raise ExprError("too much to evaluate (more than the token budget of one read)")


# Lookup of a name at a nesting depth: returns its value, or raises ExprError / the caller's error.
Lookup = Callable[[str, int], Number]
Defined = Callable[[str], bool]

# ---- tokens -----------------------------------------------------------------

_TOKEN_RE = re.compile(
    r"""(?P<ws>\s+)
      | (?P<num>\.?\d(?:[eEpP][+-]|[\w.])*)                 # a C pp-number, classified below
      | (?P<id>[A-Za-z_]\w*)
      | (?P<op>\*\*|&&|\|\||==|!=|<=|>=|<<|>>|->|\+\+|--|[-+*/%<>!~?:()&|^,.\[\]{}=;])  # ** only to name it
    """,
    re.X,
)
_INT_SUFFIX = r"(?:[uU](?:ll|LL|l|L)?|(?:ll|LL|l|L)[uU]?)?"
_DEC_RE = re.compile(r"(?:[1-9]\d*|0)" + _INT_SUFFIX)
_OCT_RE = re.compile(r"0[0-7]+" + _INT_SUFFIX)
_HEX_RE = re.compile(r"0[xX][0-9A-Fa-f]+" + _INT_SUFFIX)
_FLOAT_RE = re.compile(r"(?:(\d+\.\d*|\.\d+)(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)[fFlL]?")
_SUPPORTED_OPS = {"&&", "||", "==", "!=", "<=", ">=", "<", ">", "+", "-", "*", "/", "%", "!", "?", ":", "(", ")"}

# Cast type names: (float?, bits, signed). int is 16 bits as on the dsPIC33F (XC16), long 32:
# a value that does not fit the firmware's type is refused rather than wrapped.
_CASTS: dict[str, tuple[bool, int, bool]] = {
    "double": (True, 64, True), "float": (True, 32, True), "long double": (True, 64, True),
    "char": (False, 8, True), "signed char": (False, 8, True), "unsigned char": (False, 8, False),
    "short": (False, 16, True), "short int": (False, 16, True), "signed short": (False, 16, True),
    "unsigned short": (False, 16, False), "unsigned short int": (False, 16, False),
    "int": (False, 16, True), "signed": (False, 16, True), "signed int": (False, 16, True),
    "unsigned": (False, 16, False), "unsigned int": (False, 16, False),
    "long": (False, 32, True), "long int": (False, 32, True), "signed long": (False, 32, True),
    "unsigned long": (False, 32, False), "unsigned long int": (False, 32, False),
    "long long": (False, 64, True), "long long int": (False, 64, True),
    "unsigned long long": (False, 64, False), "unsigned long long int": (False, 64, False),
    "int8_t": (False, 8, True), "uint8_t": (False, 8, False), "int16_t": (False, 16, True),
    "uint16_t": (False, 16, False), "int32_t": (False, 32, True), "uint32_t": (False, 32, False),
    "int64_t": (False, 64, True), "uint64_t": (False, 64, False), "q15_t": (False, 16, True),
}
_TYPE_WORDS = {w for name in _CASTS for w in name.split()}


@dataclass
class _Tok:
    kind: str  # "num", "id", "op", "end"
    text: str
    value: Number = 0


def _show(text: str, limit: int = 24) -> str:
    """A token for a message: printable, short."""
    s = "".join(c if c.isprintable() else "?" for c in text)
    return repr(s if len(s) <= limit else s[:limit] + "...")


def _number(text: str) -> Number:
    if len(text) > MAX_LITERAL:
        raise ExprError(f"number literal {_show(text)} is too long")
    if _FLOAT_RE.fullmatch(text):
        value = float(text.rstrip("fFlL"))
        if not math.isfinite(value):
            raise ExprError(f"{_show(text)} is not a finite number")
        return value
    if _HEX_RE.fullmatch(text):
        base, digits = 16, text[2:]
    elif _OCT_RE.fullmatch(text):
        base, digits = 8, text
    elif _DEC_RE.fullmatch(text):
        base, digits = 10, text
    else:
        raise ExprError(f"{_show(text)} is not a C number literal")
    if "u" in text.lower():  # no hex digit is a u: this is the suffix
        raise ExprError(f"unsigned constant {_show(text)} is not supported (C converts the other operand to "
                        f"unsigned, at the dsPIC's widths or the host's; no header the tool reads has one)")
    value = int(digits.rstrip("lL"), base)
    if value >= INT_LIMIT:
        raise ExprError(f"{_show(text)} does not fit in 64 bits")
    return value


def tokenize(text: str, budget: Optional[Budget] = None) -> list[_Tok]:
    toks: list[_Tok] = []
    pos, n = 0, len(text)
    while pos < n:
        m = _TOKEN_RE.match(text, pos)
        if m is None:
            raise ExprError(f"unexpected character {_show(text[pos])}")
        pos = m.end()
        kind = m.lastgroup or ""
        if kind == "ws":
            continue
        tok = m.group(kind)
        if kind == "num":
            toks.append(_Tok("num", tok, _number(tok)))
        elif kind == "op" and tok not in _SUPPORTED_OPS:
            raise ExprError(f"operator {_show(tok)} is not supported (only + - * / % ! comparisons && || ?: casts)")
        else:
            toks.append(_Tok(kind, tok))
        if len(toks) > MAX_TOKENS:
            raise ExprError(f"more than {MAX_TOKENS} tokens")
    if budget is not None:
        budget.spend(len(toks) + 1)
    toks.append(_Tok("end", "end of the expression"))
    return toks


# ---- arithmetic with C's rules -------------------------------------------------


def _check(x: Number) -> Number:
    if isinstance(x, int):
        if not -INT_LIMIT < x < INT_LIMIT:
            raise ExprError("an integer result does not fit in 64 bits")
        return x
    if not math.isfinite(x):
        raise ExprError("a result is not a finite number (overflow or 0/0)")
    return x


def _truth(x: Number) -> bool:
    return x != 0


def _binary(op: str, a: Number, b: Number) -> Number:
    both_int = isinstance(a, int) and isinstance(b, int)
    if op == "+":
        return _check(a + b)
    if op == "-":
        return _check(a - b)
    if op == "*":
        return _check(a * b)
    if op in ("/", "%"):
        if b == 0:
            raise ExprError("division by zero")
        if op == "%" and not both_int:
            raise ExprError("% needs integer operands")
        if both_int:
            assert isinstance(a, int) and isinstance(b, int)
            q = abs(a) // abs(b)  # C truncates toward zero
            q = q if (a >= 0) == (b >= 0) else -q
            return q if op == "/" else a - b * q
        return _check(a / b)
    if op == "<":
        return int(a < b)
    if op == ">":
        return int(a > b)
    if op == "<=":
        return int(a <= b)
    if op == ">=":
        return int(a >= b)
    if op == "==":
        return int(a == b)
    if op == "!=":
        return int(a != b)
    raise ExprError(f"operator {_show(op)} is not supported")  # not reached: the tokenizer refuses it


def _cast(type_name: str, x: Number) -> Number:
    is_float, bits, signed = _CASTS[type_name]
    if is_float:
        return float(x)
    v = math.trunc(x)  # C converts a floating value to an integer type by truncation
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
    if not lo <= v <= hi:
        raise ExprError(f"({type_name}) of {x!r} is outside that type's range {lo}..{hi}")
    return v


# Binary operators by precedence, loosest first (C's order).
_PREC = {"||": 1, "&&": 2, "==": 3, "!=": 3, "<": 4, ">": 4, "<=": 4, ">=": 4, "+": 5, "-": 5,
         "*": 6, "/": 6, "%": 6}


# How the parser treats an operand: VALUE computes it; TYPE (the arm of ?: not taken) only
# types it, int or float, since the result of ?: takes the usual arithmetic conversions
# of both arms (its names are looked up for their type, nothing is computed: no division
# by zero); SKIP (the right of a decided && or ||, whose type does not matter) parses it.
VALUE, TYPE, SKIP = "value", "type", "skip"


def _typed(x: Number) -> Number:
    """A value standing for x's type only (an operand of TYPE)."""
    return 0.0 if isinstance(x, float) else 0


class _Parser:
    """Precedence climbing that evaluates as it parses. Operands that C would not
    evaluate are parsed in the TYPE or SKIP mode: checked for syntax, never computed."""

    def __init__(self, toks: list[_Tok], lookup: Lookup, defined: Optional[Defined], depth: int,
                 integer_only: bool = False):
        self.toks, self.pos, self.lookup, self.defined, self.depth = toks, 0, lookup, defined, depth
        self.integer_only = integer_only

    def peek(self) -> _Tok:
        return self.toks[self.pos]

    def take(self) -> _Tok:
        t = self.toks[self.pos]
        if t.kind != "end":
            self.pos += 1
        return t

    def expect(self, text: str) -> None:
        t = self.take()
        if t.text != text or t.kind == "end":
            raise ExprError(f"expected {text!r}, found {_show(t.text)}")

    def enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_NESTING:
            raise ExprError(f"nested more than {MAX_NESTING} deep (parentheses, operators and macros)")

    def leave(self) -> None:
        self.depth -= 1

    def expr(self, mode: str) -> Number:
        self.enter()
        cond = self.binary(1, mode)
        if self.peek().text == "?" and self.peek().kind == "op":
            self.take()
            take_first = mode == VALUE and _truth(cond)
            arm = {VALUE: TYPE, TYPE: TYPE, SKIP: SKIP}[mode]  # the arm not taken
            a = self.expr(VALUE if take_first else arm)
            self.expect(":")
            b = self.expr(VALUE if mode == VALUE and not take_first else arm)
            cond = a if take_first else b
            if isinstance(a, float) or isinstance(b, float):  # C's usual arithmetic conversions
                cond = float(cond)
        self.leave()
        return cond

    def binary(self, min_prec: int, mode: str) -> Number:
        lhs = self.unary(mode)
        while True:
            t = self.peek()
            prec = _PREC.get(t.text) if t.kind == "op" else None
            if prec is None or prec < min_prec:
                return lhs
            self.take()
            if t.text in ("&&", "||"):
                # 0 && x and 1 || x are decided: x is not evaluated (an int either way)
                decided = mode != VALUE or _truth(lhs) == (t.text == "||")
                rhs = self.binary(prec + 1, SKIP if decided else VALUE)
                if mode == VALUE:
                    lhs = int(t.text == "||") if decided else int(_truth(rhs))
                else:
                    lhs = 0
            else:
                rhs = self.binary(prec + 1, mode)
                if mode == VALUE:
                    lhs = _binary(t.text, lhs, rhs)
                elif t.text in ("+", "-", "*", "/", "%"):
                    if t.text == "%" and mode == TYPE and (isinstance(lhs, float) or isinstance(rhs, float)):
                        raise ExprError("% needs integer operands")  # a type error, evaluated or not
                    lhs = _typed(lhs) + _typed(rhs)  # float if either is
                else:
                    lhs = 0  # a comparison is an int

    def cast_type(self) -> Optional[str]:
        """At '(': the type name of a cast, consumed with its ')', or None (a parenthesis)."""
        i = self.pos + 1
        words: list[str] = []
        while self.toks[i].kind == "id" and self.toks[i].text in _TYPE_WORDS:
            words.append(self.toks[i].text)
            i += 1
        if not words or self.toks[i].text != ")" or self.toks[i].kind != "op":
            return None
        name = " ".join(words)
        if name not in _CASTS:
            raise ExprError(f"cast to {_show(name)} is not supported")
        if self.integer_only:
            raise ExprError(f"cast to {_show(name)} in #if (the preprocessor reads a type name as 0)")
        if not _CASTS[name][2]:
            raise ExprError(f"cast to {_show(name)}: unsigned types are not supported (C's unsigned conversions "
                            f"differ between the dsPIC and the host; no header the tool reads has one)")
        self.pos = i + 1
        return name

    def unary(self, mode: str) -> Number:
        t = self.peek()
        if t.kind == "op" and t.text in ("+", "-", "!"):
            self.take()
            self.enter()
            v = self.unary(mode)
            self.leave()
            if t.text == "!":
                return int(not _truth(v)) if mode == VALUE else 0
            if mode != VALUE:
                return _typed(v)
            return v if t.text == "+" else _check(-v)
        if t.kind == "op" and t.text == "(":
            type_name = self.cast_type()
            if type_name is not None:
                self.enter()
                v = self.unary(mode)
                self.leave()
                if mode == VALUE:
                    return _cast(type_name, v)
                return 0.0 if _CASTS[type_name][0] else 0
            self.take()
            v = self.expr(mode)
            self.expect(")")
            return v
        return self.primary(mode)

    def primary(self, mode: str) -> Number:
        t = self.take()
        if t.kind == "num":
            if self.integer_only and isinstance(t.value, float):
                raise ExprError(f"floating constant {_show(t.text)} in #if (C allows integers only)")
            return t.value if mode == VALUE else _typed(t.value)
        if t.kind == "id":
            if t.text == "defined" and self.defined is not None:
                paren = self.peek().text == "("
                if paren:
                    self.take()
                name = self.take()
                if name.kind != "id":
                    raise ExprError(f"defined needs a macro name, found {_show(name.text)}")
                if paren:
                    self.expect(")")
                return int(self.defined(name.text)) if mode == VALUE else 0
            if self.peek().text == "(" and self.peek().kind == "op":
                raise ExprError(f"{_show(t.text)}(...): calls are not supported")
            if t.text in _TYPE_WORDS:
                raise ExprError(f"{_show(t.text)} is a type name, not a value")
            if mode == SKIP:
                return 0
            v = self.lookup(t.text, self.depth + 1)
            return v if mode == VALUE else _typed(v)
        if t.kind == "end":
            raise ExprError("the expression ends too early" if self.pos else "empty expression")
        raise ExprError(f"unexpected {_show(t.text)}")


def evaluate(text: str, lookup: Lookup, depth: int = 0, defined: Optional[Defined] = None,
             budget: Optional[Budget] = None, integer_only: bool = False) -> Number:
    """The value of the C constant expression `text`. Names go to lookup(name, depth)
    (depth: the nesting so far, to pass back here for the name's own expression). With
    `defined` (the #if form), `defined X` and `defined(X)` are recognised; integer_only
    (#if, and the macros it expands) refuses floating constants and casts."""
    if depth > MAX_NESTING:
        raise ExprError(f"macros nested more than {MAX_NESTING} deep")
    toks = tokenize(text, budget)
    p = _Parser(toks, lookup, defined, depth, integer_only)
    v = p.expr(VALUE)
    t = p.peek()
    if t.kind != "end":
        raise ExprError(f"unexpected {_show(t.text)} after the expression")
    return v
