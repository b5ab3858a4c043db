# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Quantities with units: "5.34 ohm", "3.84 mH", "7.3 V/krpm", "1.64 A".

Every physical value in a motor description carries its unit, either in the
string ("5.34 ohm") or, for a bare number, in the key name ("resistance_ohm").
A unit that is not known for the quantity is an error that names the field;
a bare number without a unit in its key is an error too (no silent guessing),
and so is a key and a string that name different units. Unit names match in
any case; the milli prefix only as "m" ("MOhm" would be mega, never milli).
"""

from __future__ import annotations

import math
import re
import unicodedata
from typing import Any

# A profile or board name: it becomes a file name (motor_<name>.h), a C include guard
# (MOTOR_<NAME>_H), a -D option (MC_MOTOR_<NAME>) and a make variable, so only what is
# safe in all four: a lower-case C identifier, 32 characters at most.
NAME_RE = re.compile(r"[a-z][a-z0-9_]{0,31}")

MAX_MESSAGE = 300  # characters of one error line

# The constants every module shares (one home, so the tool and its replay of the core agree).
SQRT2 = math.sqrt(2.0)
SQRT3 = math.sqrt(3.0)
TWO_PI = 2.0 * math.pi
RPM = TWO_PI / 60.0  # rad/s per rpm


def one_line(text: str, limit: int = MAX_MESSAGE) -> str:
    """text as one printable line: control characters (a newline in a TOML key, a file
    name) are shown escaped, never printed, and a long text is cut."""
    out = []
    for c in text:
        if c.isprintable() or c == " ":
            out.append(c)
        else:
            out.append(c.encode("unicode_escape").decode("ascii"))
    s = "".join(out)
    return s if len(s) <= limit else s[: limit - 3] + "..."


class InputError(Exception):
    """A problem with the input: the message (one line) starts with the field name."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(one_line(f"{field}: {message}"))
        self.field = field


# Unit spellings per quantity, to the SI factor (spaces and '*' / '.' between factors
# removed). Unit names match in any case ("OHM", "kRPM", "KHz"); a prefix written in
# brackets matches only in that case: "[m]" is milli, and "M" (mega) is another prefix,
# so "5.34 MOhm" is not read as 5.34 milliohm. Plurals and common variants are accepted;
# NFKC folds the ohm sign U+2126 into the Greek capital omega and the micro sign into mu.
_SPELLINGS: dict[str, dict[str, float]] = {
    "resistance": {
        "ohm": 1.0, "ohms": 1.0, "\u03a9": 1.0,
        "[m]ohm": 1e-3, "[m]ohms": 1e-3, "milliohm": 1e-3, "milliohms": 1e-3, "[m]\u03a9": 1e-3,
    },
    "inductance": {
        "H": 1.0, "henry": 1.0, "henries": 1.0, "henrys": 1.0,
        "[m]H": 1e-3, "millihenry": 1e-3, "millihenries": 1e-3,
        "uH": 1e-6, "\u03bcH": 1e-6, "microhenry": 1e-6,
    },
    # back-EMF constant, to volts per 1000 rpm
    "back_emf": {
        "V/krpm": 1.0, "V/1000rpm": 1.0, "V/rpm": 1000.0, "[m]V/rpm": 1.0,
        "V/(rad/s)": 1000.0 * RPM, "Vs/rad": 1000.0 * RPM, "V/rad/s": 1000.0 * RPM,
    },
    "current": {"A": 1.0, "amp": 1.0, "amps": 1.0, "ampere": 1.0, "amperes": 1.0, "[m]A": 1e-3},
    "torque": {"Nm": 1.0, "[m]Nm": 1e-3, "Ncm": 1e-2},
    "speed": {"rpm": 1.0, "krpm": 1000.0, "r/min": 1.0, "rev/min": 1.0},
    "inertia": {
        "kgm^2": 1.0, "kgm2": 1.0, "kgcm^2": 1e-4, "kgcm2": 1e-4,
        "gcm^2": 1e-7, "gcm2": 1e-7, "kg[m]m^2": 1e-6, "kg[m]m2": 1e-6,
        "oz-in-s^2": 7.0615518e-3, "ozins^2": 7.0615518e-3,
    },
    "frequency": {"Hz": 1.0, "kHz": 1e3},
    "angular_rate": {"rad/s": 1.0, "Hz": TWO_PI, "kHz": TWO_PI * 1e3},
}


class _Spelling:
    """One spelling: its characters, which of them must match in case, its SI factor."""

    def __init__(self, written: str, factor: float) -> None:
        self.strict: set[int] = set()
        chars: list[str] = []
        i = 0
        while i < len(written):
            if written[i] == "[":
                self.strict.add(len(chars))
                chars.append(written[i + 1])
                i += 3
            else:
                chars.append(written[i])
                i += 1
        self.text, self.factor = "".join(chars), factor

    def matches(self, unit: str, strict: bool = True) -> bool:
        return len(unit) == len(self.text) and all(
            a == b if strict and k in self.strict else a.casefold() == b.casefold()
            for k, (a, b) in enumerate(zip(unit, self.text, strict=False)))


_UNITS = {q: [_Spelling(w, f) for w, f in table.items()] for q, table in _SPELLINGS.items()}

# Key-name suffixes that give the unit of a bare number ("resistance_ohm = 5.34"), to the SI factor.
_SUFFIX_UNITS: dict[str, dict[str, float]] = {
    "resistance": {"_ohm": 1.0, "_mohm": 1e-3},
    "inductance": {"_h": 1.0, "_mh": 1e-3, "_uh": 1e-6},
    "back_emf": {"_v_per_krpm": 1.0, "_v_per_rpm": 1000.0},
    "current": {"_a": 1.0, "_ma": 1e-3},
    "torque": {"_nm": 1.0, "_mnm": 1e-3},
    "speed": {"_rpm": 1.0, "_krpm": 1000.0},
    "inertia": {"_kgm2": 1.0, "_kg_m2": 1.0, "_kgcm2": 1e-4, "_gcm2": 1e-7},
    "frequency": {"_hz": 1.0, "_khz": 1e3},
    "angular_rate": {"_rad_s": 1.0, "_hz": TWO_PI},
}

# What a value of each quantity looks like (the hint of an error): a plausible motor's.
_EXAMPLES = {
    "resistance": "2.67 ohm", "inductance": "1.92 mH", "back_emf": "7.3 V/krpm", "current": "1.64 A",
    "speed": "2700 rpm", "inertia": "7.5e-6 kg m^2", "frequency": "20 kHz", "angular_rate": "3000 rad/s",
    "torque": "50 mN m",
}

MAX_QUANTITY_TEXT = 64  # characters of "number unit" ("7.5e-6 kg m^2" has 13)
_NUM_RE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def _norm_unit(u: str) -> str:
    u = u.strip().replace("\u00b2", "^2").replace("**", "^")
    u = unicodedata.normalize("NFKC", u)
    return re.sub(r"[\s*\u00b7]", "", u)  # "kg m^2", "kg*m^2", "kg·m^2" -> "kgm^2"


def _known(quantity: str, every: bool = True) -> str:
    """The quantity's units for a message: every spelling, or the first of each factor."""
    seen: set[float] = set()
    out = []
    for s in _UNITS[quantity]:
        if every or s.factor not in seen:
            out.append(s.text)
            seen.add(s.factor)
    return ", ".join(out)


def base_key(key: str, quantity: str) -> str:
    """The key without a unit suffix ("resistance_ohm" -> "resistance")."""
    suf = _key_suffix(key, quantity)
    return key[: -len(suf)] if suf else key


def _key_suffix(key: str, quantity: str) -> str:
    """The unit suffix the key ends with ("" if none); the longest wins (_mohm, not _ohm)."""
    for suf in sorted(_SUFFIX_UNITS.get(quantity, {}), key=len, reverse=True):
        if key.endswith(suf) and len(key) > len(suf):
            return suf
    return ""


def _no_unit(field: str, what: str, quantity: str, key: str) -> InputError:
    """A number without a unit: the hint is a value of this quantity, never the number
    with a guessed unit (20000 is not "20000 kHz")."""
    sufs = ", ".join(key + s for s in _SUFFIX_UNITS[quantity])
    return InputError(field, f"{what} needs a unit: write it as a string with one, e.g. {key} = "
                             f"\"{_EXAMPLES[quantity]}\" (units: {_known(quantity, every=False)}), or name the unit in "
                             f"the key ({sufs})")


def _unit_factor(field: str, written: str, quantity: str) -> float:
    """The SI factor of a unit as written ("mOhm"); InputError naming the field otherwise."""
    unit = _norm_unit(written)
    for s in _UNITS[quantity]:
        if s.matches(unit):
            return s.factor
    what = quantity.replace("_", " ")
    if any(s.matches(unit, strict=False) for s in _UNITS[quantity]):
        raise InputError(field, f"unknown unit {written!r} for {what}: SI prefixes are case-sensitive "
                                f"(m is milli, M mega; use one of: {_known(quantity)})")
    raise InputError(field, f"unknown unit {written!r} for {what} (use one of: {_known(quantity)})")


def parse(field: str, value: Any, quantity: str, key: str | None = None) -> float:
    """Value of `field` (a number or a "number unit" string) in SI units
    (back-EMF: V per 1000 rpm; speed: rpm; angular rate: rad/s). The unit is in the
    string, or in the key's suffix (resistance_ohm = 5.34, or "5.34"); both at once must
    agree (resistance_mohm = "5.34 ohm" is refused: which one was meant?)."""
    key = key if key is not None else field.split(".")[-1]
    suf = _key_suffix(key, quantity)
    key_factor = _SUFFIX_UNITS[quantity][suf] if suf else None
    base = base_key(key, quantity)
    if isinstance(value, bool):
        raise InputError(field, f"expected a {quantity.replace('_', ' ')} with a unit, got {value!r}")
    if isinstance(value, (int, float)):
        if key_factor is None:
            raise _no_unit(field, f"the bare number {value!r}", quantity, base)
        try:
            number, factor = float(value), key_factor
        except OverflowError:  # a TOML integer of hundreds of digits
            raise InputError(field, "is not a finite number") from None
    elif isinstance(value, str):
        if len(value) > MAX_QUANTITY_TEXT:  # also keeps the regular expression's work small
            raise InputError(field, f"{len(value)} characters: too long for a number and a unit")
        m = _NUM_RE.match(value)
        if not m:
            raise InputError(field, f"cannot read {value!r} as a number and a unit")
        number = float(m.group(1))
        if not m.group(2):
            if key_factor is None:
                raise _no_unit(field, repr(value), quantity, base)
            factor = key_factor
        else:
            factor = _unit_factor(field, m.group(2), quantity)
            if key_factor is not None and not math.isclose(factor, key_factor):
                raise InputError(field, f"the key says {suf[1:]}, the value {value!r} says {m.group(2)}: give the "
                                        f"unit once ({base} = \"{value}\")")
    else:
        raise InputError(field, f"expected a number with a unit, got {type(value).__name__}")
    if not math.isfinite(number) or not math.isfinite(number * factor):
        raise InputError(field, f"{value!r} is not a finite number")
    return number * factor
