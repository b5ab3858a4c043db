"""Quantities with units: "5.34 ohm", "3.84 mH", "7.3 V/krpm", "1.64 A".

Every physical value in a motor description carries its unit, either in the
string ("5.34 ohm") or, for a bare number, in the key name ("resistance_ohm").
A unit that is not known for the quantity is an error that names the field;
a bare number without a unit in its key is an error too (no silent guessing).
"""

from __future__ import annotations

import math
import re
from typing import Any, Optional

# A profile or board name: it becomes a file name (motor_<name>.h), a C include guard
# (MOTOR_<NAME>_H), a -D option (MC_MOTOR_<NAME>) and a make variable, so only what is
# safe in all four: a lower-case C identifier, 32 characters at most.
NAME_RE = re.compile(r"[a-z][a-z0-9_]{0,31}")

MAX_MESSAGE = 300  # characters of one error line


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

    def __init__(self, field: str, message: str):
        super().__init__(one_line(f"{field}: {message}"))
        self.field = field


# Unit spellings (lower case, spaces and '*' / '.' between factors removed)
# per quantity, to the SI factor. Plurals and common variants are accepted.
_UNITS = {
    "resistance": {
        "ohm": 1.0, "ohms": 1.0, "\u03c9": 1.0, "\u2126": 1.0,
        "mohm": 1e-3, "mohms": 1e-3, "milliohm": 1e-3, "milliohms": 1e-3,
        "m\u03c9": 1e-3, "m\u2126": 1e-3,
    },
    "inductance": {
        "h": 1.0, "henry": 1.0, "henries": 1.0, "henrys": 1.0,
        "mh": 1e-3, "millihenry": 1e-3, "millihenries": 1e-3,
        "uh": 1e-6, "\u00b5h": 1e-6, "\u03bch": 1e-6, "microhenry": 1e-6,
    },
    # back-EMF constant, to volts per 1000 rpm
    "back_emf": {
        "v/krpm": 1.0, "v/1000rpm": 1.0, "v/rpm": 1000.0,
        "mv/rpm": 1.0, "v/(rad/s)": 1000.0 * 2.0 * math.pi / 60.0,
        "vs/rad": 1000.0 * 2.0 * math.pi / 60.0, "v/rad/s": 1000.0 * 2.0 * math.pi / 60.0,
    },
    "current": {"a": 1.0, "amp": 1.0, "amps": 1.0, "ampere": 1.0, "amperes": 1.0, "ma": 1e-3},
    "torque": {"nm": 1.0, "mnm": 1e-3, "ncm": 1e-2},
    "speed": {"rpm": 1.0, "krpm": 1000.0, "r/min": 1.0, "rev/min": 1.0},
    "inertia": {
        "kgm^2": 1.0, "kgm2": 1.0, "kgcm^2": 1e-4, "kgcm2": 1e-4,
        "gcm^2": 1e-7, "gcm2": 1e-7, "kgmm^2": 1e-6, "kgmm2": 1e-6,
        "oz-in-s^2": 7.0615518e-3, "ozins^2": 7.0615518e-3,
    },
    "frequency": {"hz": 1.0, "khz": 1e3},
    "angular_rate": {"rad/s": 1.0, "hz": 2.0 * math.pi, "khz": 2.0 * math.pi * 1e3},
    "time": {"s": 1.0, "sec": 1.0, "ms": 1e-3},
    "voltage": {"v": 1.0, "volt": 1.0, "volts": 1.0},
    "ratio": {"": 1.0, "%": 0.01},
}

# Key-name suffixes that give the unit of a bare number ("resistance_ohm = 5.34").
_SUFFIX_UNITS = {
    "resistance": {"_ohm": "ohm", "_mohm": "mohm"},
    "inductance": {"_h": "h", "_mh": "mh", "_uh": "uh"},
    "back_emf": {"_v_per_krpm": "v/krpm", "_v_per_rpm": "v/rpm"},
    "current": {"_a": "a", "_ma": "ma"},
    "torque": {"_nm": "nm", "_mnm": "mnm"},
    "speed": {"_rpm": "rpm", "_krpm": "krpm"},
    "inertia": {"_kgm2": "kgm^2", "_kg_m2": "kgm^2", "_kgcm2": "kgcm^2", "_gcm2": "gcm^2"},
    "frequency": {"_hz": "hz", "_khz": "khz"},
    "angular_rate": {"_rad_s": "rad/s", "_hz": "hz"},
    "time": {"_s": "s", "_ms": "ms"},
    "voltage": {"_v": "v"},
    "ratio": {"": ""},
}

MAX_QUANTITY_TEXT = 64  # characters of "number unit" ("7.5e-6 kg m^2" has 13)
_NUM_RE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def _norm_unit(u: str) -> str:
    u = u.strip().lower()
    u = u.replace("\u00b2", "^2").replace("**", "^")
    u = re.sub(r"[\s*\u00b7]", "", u)  # "kg m^2", "kg*m^2", "kg·m^2" -> "kgm^2"
    return u


def base_key(key: str, quantity: str) -> str:
    """The key without a unit suffix ("resistance_ohm" -> "resistance")."""
    for suf in sorted(_SUFFIX_UNITS.get(quantity, {}), key=len, reverse=True):
        if suf and key.endswith(suf):
            return key[: -len(suf)]
    return key


def parse(field: str, value: Any, quantity: str, key: Optional[str] = None) -> float:
    """Value of `field` (a number or a "number unit" string) in SI units
    (back-EMF: V per 1000 rpm; speed: rpm; angular rate: rad/s)."""
    table = _UNITS[quantity]
    key = key if key is not None else field.split(".")[-1]
    if isinstance(value, bool):
        raise InputError(field, f"expected a {quantity.replace('_', ' ')} with a unit, got {value!r}")
    if isinstance(value, (int, float)):
        unit = None
        for suf, u in _SUFFIX_UNITS.get(quantity, {}).items():
            if key.endswith(suf):
                unit = u
                break
        if unit is None:
            raise InputError(
                field,
                f"the number {value!r} needs a unit: write it as a string, e.g. "
                f'"{value} {_example_unit(quantity)}"',
            )
        try:
            number, factor = float(value), table[unit]
        except OverflowError:  # a TOML integer of hundreds of digits
            raise InputError(field, "is not a finite number") from None
    elif isinstance(value, str):
        if len(value) > MAX_QUANTITY_TEXT:  # also keeps the regular expression's work small
            raise InputError(field, f"{len(value)} characters: too long for a number and a unit")
        m = _NUM_RE.match(value)
        if not m:
            raise InputError(field, f"cannot read {value!r} as a number and a unit")
        number = float(m.group(1))
        unit = _norm_unit(m.group(2))
        if unit == "" and quantity != "ratio":
            raise InputError(
                field, f"{value!r} has no unit (e.g. \"{m.group(1)} {_example_unit(quantity)}\")"
            )
        found = table.get(unit)
        if found is None:
            known = ", ".join(sorted({k for k, v in table.items() if v is not None and k}))
            raise InputError(
                field, f"unknown unit {m.group(2)!r} for {quantity.replace('_', ' ')} (use one of: {known})"
            )
        factor = found
    else:
        raise InputError(field, f"expected a number with a unit, got {type(value).__name__}")
    if not math.isfinite(number) or not math.isfinite(number * factor):
        raise InputError(field, f"{value!r} is not a finite number")
    return number * factor


def _example_unit(quantity: str) -> str:
    return {
        "resistance": "ohm", "inductance": "mH", "back_emf": "V/krpm", "current": "A",
        "speed": "rpm", "inertia": "kg m^2", "frequency": "kHz", "angular_rate": "rad/s",
        "torque": "N m", "time": "s", "voltage": "V", "ratio": "%",
    }[quantity]
