# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""The motor description file (TOML): fields, units, validation.

    name = "hurst075"            # profile name: firmware/motors/motor_<name>.h
    description = "..."          # optional, becomes MOTOR_NAME
    board = "mclv"               # boards/board_<board>.h
    pwm_frequency = "20 kHz"     # optional (boards/board.h default otherwise)

    [motor]
    pole_pairs = 5
    resistance = "5.34 ohm"      resistance_kind = "line-to-line" | "per-phase"
    inductance = "3.84 mH"       inductance_kind = "line-to-line" | "per-phase"
    back_emf = "7.3 V/krpm"      back_emf_kind = "peak line-to-line" | "rms line-to-line"
                                                 | "peak phase" | "rms phase"
    rated_current = "1.64 A"     current_kind = "peak" | "rms"
    rated_speed = "2700 rpm"
    peak_current = "3.0 A"       # optional: short-term limit (field weakening)
    inertia = "7.5e-6 kg m^2"    # optional: rotor plus coupled load

    [application]                # all optional
    max_speed = "5300 rpm"       # top speed asked for (field weakening above nominal)
    min_speed = "500 rpm"        # lowest closed-loop speed (else derived)
    current_bandwidth = "4000 rad/s"
    fw_load_current = "0.4 A"    # Iq the field-weakening table is computed for
    start_load = "0.02 N m"      # torque the load needs at start (breakaway, and at the
                                 # ramp end): the start-up current is sized for it

    [tuning]                     # optional: hand-tuned choices, each replacing one derived value
    # the reason, in the comment line(s) right above the key: written into the header
    MOTOR_SPEED_NOMINAL_RPM = 2500.0        # a macro the profile defines = a number in its unit
    MOTOR_FW_ID_TABLE_A = [0.0, -0.4, ...]  # the field-weakening table: 16 numbers, A
    MOTOR_NAME = "..."                      # the profile's MOTOR_NAME (else `description`)

[tuning] keys are the header's macro names (TUNABLE), bare keys on their own line,
each with its reason in a comment above it; the motor's data (R, L, Ke, pole pairs,
rated current, inertia) are not among them: their one home is [motor]. A value is
written into the header as given (the shortest text of the same double) and judged
by the core's checks through the probe; it is not fed back into the derivation
(tools/tune --no-tuning writes the profile without them).

A bare number is accepted when the key carries the unit ("resistance_ohm =
2.67"). Every problem raises InputError naming the field: an unknown or
missing field, a unit that is not one of the quantity's, a number that is not
finite or outside what any motor this firmware drives could have (PLAUSIBLE),
an inertia that does not fit the motor's own torque (a unit slip, with the
unit that would fit), a name that is not a safe C identifier, a description
with characters that do not belong in a C string or comment.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import re
import tomllib
from typing import Any

from . import safeio, units
from .units import NAME_RE, RPM, SQRT2, SQRT3, InputError

MAX_TOML_BYTES = 64 * 1024  # the examples are 1..2 kB
MAX_DESCRIPTION = 100  # characters of `description` (MOTOR_NAME, and the header's first line)

# field -> (quantity, required)
TOP = {"name": ("text", True), "description": ("text", False), "board": ("text", True),
       "pwm_frequency": ("frequency", False)}
MOTOR = {
    "pole_pairs": ("int", True),
    "resistance": ("resistance", True), "resistance_kind": ("kind_ll", True),
    "inductance": ("inductance", True), "inductance_kind": ("kind_ll", True),
    "back_emf": ("back_emf", True), "back_emf_kind": ("kind_emf", True),
    "rated_current": ("current", True), "current_kind": ("kind_cur", True),
    "rated_speed": ("speed", True),
    "peak_current": ("current", False),
    "inertia": ("inertia", False),
}
APP = {
    "max_speed": ("speed", False), "min_speed": ("speed", False),
    "current_bandwidth": ("angular_rate", False), "fw_load_current": ("current", False),
    "start_load": ("torque", False),
}
SECTIONS = {"": TOP, "motor": MOTOR, "application": APP}
TUNING_SECTION = "tuning"

# [tuning]: the macros a description may set by hand (emit.SECTIONS' order), and the
# unit each is in; MOTOR_FW_ID_TABLE_A is 16 numbers, MOTOR_NAME a text.
TUNABLE: dict[str, str] = {
    "MOTOR_SPEED_NOMINAL_RPM": "rpm", "MOTOR_SPEED_FW_MAX_RPM": "rpm", "MOTOR_SPEED_MIN_RPM": "rpm",
    "MOTOR_SPEED_FULLSCALE_RPM": "rpm", "MOTOR_CURRENT_MAX_A": "A", "MOTOR_OVERCURRENT_A": "A",
    "MOTOR_LOCK_TIME_S": "s", "MOTOR_LOCK_CURRENT_A": "A", "MOTOR_RAMP_TIME_S": "s", "MOTOR_RAMP_END_RPM": "rpm",
    "MOTOR_RAMP_CURRENT_A": "A", "MOTOR_OL_DAMP_S": "s", "MOTOR_SMC_GAIN_V": "V", "MOTOR_SMC_LINEAR_BAND_A": "A",
    "MC_SPEED_FILTER_HZ": "Hz", "MC_DEADTIME_BAND_A": "A", "MOTOR_CURRENT_LOOP_BW_RAD_S": "rad/s",
    "MOTOR_CURRENT_KP_V_PER_A": "V/A", "MOTOR_CURRENT_KI_V_PER_AS": "V/(A s)", "MOTOR_SPEED_KP_FULL_RPM": "rpm",
    "MOTOR_SPEED_KP_A_PER_RPM": "A/rpm", "MOTOR_SPEED_KI_A_PER_RPM_S": "A/(rpm s)", "MOTOR_START_LOAD_NM": "N m",
    "MOTOR_FW_ID_TABLE_A": "A", "MOTOR_NAME": "",
}
# macros whose value is the motor's data: one home, [motor] (or [application])
DATA_HOME = {"MOTOR_POLE_PAIRS": "motor.pole_pairs", "MOTOR_RS_OHM": "motor.resistance",
             "MOTOR_LS_H": "motor.inductance", "MOTOR_KE_VPK_LL_PER_KRPM": "motor.back_emf",
             "MOTOR_RATED_CURRENT_A": "motor.rated_current", "MOTOR_INERTIA_KGM2": "motor.inertia",
             "MOTOR_TUNE_BOARD": "board"}
FW_TABLE_ENTRIES = 16
TUNING_MAX_ABS = 1e15  # any value of any of these macros is far below; a larger one is a slip


@dataclasses.dataclass(frozen=True)
class Override:
    """One [tuning] entry: the text written into the header, its number(s), the reason."""

    macro: str
    text: str  # the C text of the value (the shortest text of the same double)
    numbers: tuple[float, ...]  # the value (one number; 16 for the table)
    reason: str  # the comment above the key in the description

KINDS = {
    "kind_ll": {"line-to-line": 0.5, "per-phase": 1.0},
    # factor to peak line-to-line
    "kind_emf": {"peak line-to-line": 1.0, "rms line-to-line": SQRT2, "peak phase": SQRT3,
                 "rms phase": SQRT2 * SQRT3},
    "kind_cur": {"peak": 1.0, "rms": SQRT2},
}
_KIND_ALIASES = {"line to line": "line-to-line", "ll": "line-to-line", "l-l": "line-to-line",
                 "phase": "per-phase", "per phase": "per-phase", "phase-to-neutral": "per-phase"}


# What any motor this firmware could drive has, in the units Description holds (SI; speeds
# rpm; Ke V/krpm peak line-to-line; R, L per phase; currents A peak). Outside: a unit slip
# or a typo, refused naming the field, before any arithmetic sees a 1e300 or a 1e-300.
PLAUSIBLE: dict[str, tuple[float, float, str]] = {
    "motor.resistance": (1e-4, 1e3, "ohm"),
    "motor.inductance": (1e-7, 10.0, "H"),
    "motor.back_emf": (1e-3, 1e5, "V/krpm"),
    "motor.rated_current": (1e-3, 1e3, "A"),
    "motor.peak_current": (1e-3, 1e3, "A"),
    "motor.rated_speed": (1.0, 2e5, "rpm"),
    "motor.inertia": (1e-12, 1e3, "kg m^2"),
    "application.max_speed": (1.0, 2e5, "rpm"),
    "application.min_speed": (1.0, 2e5, "rpm"),
    "application.current_bandwidth": (1.0, 1e6, "rad/s"),
    "application.fw_load_current": (1e-3, 1e3, "A"),
    "application.start_load": (1e-6, 1e4, "N m"),
    "pwm_frequency": (1.0, 1e6, "Hz"),
}
# The time a motor takes to reach its rated speed at its rated torque, t = J w / T: a bare
# rotor a few ms (the Hurst075 with its assumed load 21 ms), a flywheel or a geared load
# seconds. Outside this window the inertia's unit is wrong (kg cm^2 is 1e-4 kg m^2, g cm^2
# 1e-7): the speed gains would round to 0 in Q15 or saturate.
ACCEL_TIME_S = (20e-6, 100.0)
_INERTIA_UNITS = (("kg m^2", 1.0), ("kg cm^2", 1e-4), ("kg mm^2", 1e-6), ("g cm^2", 1e-7))


@dataclasses.dataclass
class Description:
    """Validated motor description, SI units (speeds in rpm, Ke in V/krpm peak line-to-line,
    currents A peak, R and L per phase)."""

    name: str = ""
    desc: str = ""
    board: str = ""
    source: str = ""
    pwm_hz: float | None = None
    pole_pairs: int = 0
    r_ph: float = 0.0
    l_ph: float = 0.0
    ke_ll: float = 0.0
    i_rated: float = 0.0
    n_rated: float = 0.0
    i_peak: float | None = None
    j: float | None = None
    n_max: float | None = None
    n_min: float | None = None
    wc: float | None = None
    i_fw_load: float | None = None
    t_start: float | None = None
    tuning: dict[str, Override] = dataclasses.field(default_factory=dict)
    raw: dict[tuple[str, str], Any] = dataclasses.field(default_factory=dict)


def check_name(name: Any, field: str = "name") -> str:
    """A profile name however it arrives (the TOML `name`, --name): it becomes
    motor_<name>.h, the include guard MOTOR_<NAME>_H and MOTOR=<name>."""
    if not isinstance(name, str) or not NAME_RE.fullmatch(name):
        raise InputError(field, f"{str(name)[:40]!r}: use a lower-case letter, then lower-case letters, digits "
                                f"and _, 32 characters at most (it becomes motor_<name>.h and a C macro name)")
    return name


def check_description(text: str, field: str = "description") -> str:
    """The description goes into a C string literal (MOTOR_NAME) and the header's first
    comment: printable ASCII only (no newline, which would end the comment's line and
    could start a directive), and nothing that ends either (a double quote, a backslash,
    the comment's end) or starts a comment (which -Wcomment refuses inside one) or a
    trigraph (two question marks: ??/ is a backslash in C99)."""
    if len(text) > MAX_DESCRIPTION:
        raise InputError(field, f"{len(text)} characters: {MAX_DESCRIPTION} at most")
    for c in text:
        if not " " <= c <= "~":
            raise InputError(field, f"character {c!r} is not allowed (printable ASCII only: it is written "
                                    f"into a C string and a comment)")
    for bad in ('"', "\\", "*/", "/*", "??"):
        if bad in text:
            raise InputError(field, f"must not contain {bad} (it is written into a C string and a comment)")
    return text


def _match_key(section: str, key: str, fields: dict[str, tuple[str, bool]]) -> tuple[str, str]:
    """Canonical field of a key, allowing a unit suffix (resistance_ohm)."""
    if key in fields:
        return key, key
    shown = key if len(key) <= 40 else key[:40] + "..."
    where = f"{section}.{shown}" if section else shown
    if not key:  # "" = 1: a field with no name
        raise InputError(f'{section}.""' if section else '""',
                         f"an empty key is not a field (known: {', '.join(fields)})")
    if len(key) > 64:  # no field is that long; and difflib's work grows with the length
        raise InputError(where, "unknown field")
    for f, (q, _) in fields.items():
        if q in units._SUFFIX_UNITS and units.base_key(key, q) == f:
            return f, key
    close = difflib.get_close_matches(key, list(fields), n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]}?)" if close else f" (known: {', '.join(fields)})"
    raise InputError(where, f"unknown field{hint}")


def _read_kind(field: str, value: Any, kind: str) -> float:
    if not isinstance(value, str):
        raise InputError(field, f"expected one of {', '.join(KINDS[kind])}")
    v = value.strip().lower()
    v = _KIND_ALIASES.get(v, v)
    if kind == "kind_emf":
        v = v.replace("line to line", "line-to-line").replace(" ll", " line-to-line")
    if v not in KINDS[kind]:
        raise InputError(field, f"{value!r} is not one of: {', '.join(KINDS[kind])}")
    return KINDS[kind][v]


def load(path: str) -> Description:
    """The description in the TOML file at path: a regular file of at most MAX_TOML_BYTES."""
    if not path:
        raise InputError("file", "no description file given")
    text = safeio.read_utf8(path, "file", MAX_TOML_BYTES)
    d = parse(loads(text), tuning_comments(text))
    d.source = path
    return d


_TABLE_RE = re.compile(r"^\s*\[([^\[\]]*)\]\s*(#.*)?$")
_KEY_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*=")


def tuning_comments(text: str) -> dict[str, str]:
    """The reason of each [tuning] key: the comment lines right above it (a blank line
    or another key ends a reason). tomllib drops comments, so they are read here from the
    lines; what this reads is only ever written inside a comment (emit.comment_text)."""
    out: dict[str, str] = {}
    section: str | None = None
    pending: list[str] = []
    for line in text.splitlines():
        m = _TABLE_RE.match(line)
        if m:
            section = m.group(1).strip()
            pending = []
            continue
        if section != TUNING_SECTION:
            continue
        stripped = line.strip()
        if stripped.startswith("#"):
            pending.append(stripped.lstrip("#").strip())
            continue
        k = _KEY_RE.match(line)
        if k:
            reason = " ".join(p for p in pending if p)
            if reason:
                out.setdefault(k.group(1), reason)
            pending = []
        elif not stripped:
            pending = []
    return out


def _tuning_number(where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(where, f"expected a number in the macro's unit, got {str(value)[:40]!r}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf
    if not math.isfinite(x) or abs(x) > TUNING_MAX_ABS:
        raise InputError(where, f"{str(value)[:40]}: not a finite number of plausible size")
    return x


def _c_number(x: float) -> str:
    """x as a C double literal of the same value (repr is the shortest text that reads back
    as x); always with a point or an exponent, so C never computes it as an integer."""
    s = repr(x)
    return s if ("." in s or "e" in s) else s + ".0"


def parse_tuning(table: Any, reasons: dict[str, str]) -> dict[str, Override]:
    """[tuning]: macro name = value, each with its reason (InputError naming tuning.<key>)."""
    if not isinstance(table, dict):
        raise InputError(TUNING_SECTION, "must be a [tuning] section")
    out: dict[str, Override] = {}
    for key, value in table.items():
        shown = key if len(key) <= 40 else key[:40] + "..."
        where = f"{TUNING_SECTION}.{shown}"
        if key in DATA_HOME:
            raise InputError(where, f"the motor's data has one home, {DATA_HOME[key]}: set it there")
        if key not in TUNABLE:
            close = difflib.get_close_matches(key, list(TUNABLE), n=1, cutoff=0.6) if len(key) <= 64 else []
            hint = f" (did you mean {close[0]}?)" if close else " (a macro the profile defines: docs/tune.md)"
            raise InputError(where, f"unknown field{hint}")
        reason = reasons.get(key, "")
        if not reason:
            raise InputError(where, "say why: a comment on the line(s) right above it (it is written into the "
                                    "header as the reason)")
        if key == "MOTOR_NAME":
            if not isinstance(value, str) or not value.strip():
                raise InputError(where, "expected a non-empty string")
            name = check_description(value.strip(), where)
            out[key] = Override(key, name, (), reason)
            continue
        if key == "MOTOR_FW_ID_TABLE_A":
            if not isinstance(value, list) or len(value) != FW_TABLE_ENTRIES:
                raise InputError(where, f"expected a list of {FW_TABLE_ENTRIES} numbers (Id in A, from the "
                                        f"nominal to the top speed)")
            nums = tuple(_tuning_number(f"{where}[{k}]", v) for k, v in enumerate(value))
            text = " ".join(f"X({_c_number(x)})" for x in nums)
            out[key] = Override(key, text, nums, reason)
            continue
        x = _tuning_number(where, value)
        out[key] = Override(key, _c_number(x), (x,), reason)
    return out


def loads(text: str) -> dict[str, Any]:
    """TOML text to a dict; every problem (syntax, an integer of thousands of digits,
    arrays nested thousands deep) an InputError on the field "file" (the caller names
    the file itself, once)."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise InputError("file", f"not valid TOML ({e})") from None
    except ValueError:  # tomllib: an integer of more than 4300 digits (Python's int-from-text limit)
        raise InputError("file", "a number with too many digits") from None
    except (RecursionError, MemoryError):  # arrays or inline tables nested thousands deep
        raise InputError("file", "nested too deeply") from None


def _inertia_check(d: Description, given: Any) -> None:
    """motor.inertia against the motor's own torque: ACCEL_TIME_S bounds the time the
    rated torque takes to bring J to the rated speed. Outside it, the units that would
    put the same number inside are suggested."""
    if d.j is None:
        return
    psi = d.ke_ll / SQRT3 / (1000.0 * RPM * d.pole_pairs)  # Wb
    torque = 1.5 * d.pole_pairs * psi * d.i_rated  # N m at the rated current
    w = d.n_rated * RPM  # rad/s
    t_acc = d.j * w / torque
    lo, hi = ACCEL_TIME_S
    if lo <= t_acc <= hi:
        return
    if isinstance(given, str):
        m = units._NUM_RE.match(given)
        number = float(m.group(1)) if m else d.j
    else:
        number = float(given)
    fits = [f'"{number:g} {u}"' for u, f in _INERTIA_UNITS
            if number > 0 and lo <= number * f * w / torque <= hi]
    hint = f"; did you mean {' or '.join(fits)}?" if fits else "; check its unit (kg cm^2 = 1e-4 kg m^2, g cm^2 = 1e-7)"
    raise InputError("motor.inertia", f"{d.j:.3g} kg m^2 would reach the rated {d.n_rated:g} rpm in "
                     f"{t_acc:.3g} s at the rated torque {torque:.3g} N m; a motor with its load takes "
                     f"{lo:g} .. {hi:g} s{hint}")


def parse(data: dict[str, Any], reasons: dict[str, str] | None = None) -> Description:
    """The description in data (a TOML document); reasons: the [tuning] keys' comments
    (tuning_comments), without which a [tuning] entry is refused."""
    if not isinstance(data, dict):
        raise InputError("file", "not a TOML table")
    vals: dict[tuple[str, str], Any] = {}
    given: dict[tuple[str, str], Any] = {}  # the values as written, for hints
    for sec, fields in SECTIONS.items():
        table = data if sec == "" else data.get(sec, {})
        if sec and not isinstance(table, dict):
            raise InputError(sec, "must be a [section]")
        for key, value in table.items():
            if sec == "" and key == TUNING_SECTION:
                continue
            if sec == "" and key and key in SECTIONS:
                if isinstance(value, dict):
                    continue
                raise InputError(key, f"must be a [{key}] section, got {type(value).__name__}")
            field, k = _match_key(sec, key, fields)
            where = f"{sec}.{key}" if sec else key
            qty = fields[field][0]
            if (sec, field) in vals:
                raise InputError(where, "given twice (with and without a unit suffix)")
            v: Any
            if qty == "text":
                if not isinstance(value, str) or not value.strip():
                    raise InputError(where, "expected a non-empty string")
                v = value.strip()
            elif qty == "int":
                if not isinstance(value, int) or isinstance(value, bool):
                    raise InputError(where, f"expected a whole number, got {value!r}")
                v = value
            elif qty.startswith("kind_"):
                v = _read_kind(where, value, qty)
            else:
                v = units.parse(where, value, qty, key=k)
            vals[(sec, field)] = v
            given[(sec, field)] = value
        for field, (_, required) in fields.items():
            if required and (sec, field) not in vals:
                where = f"{sec}.{field}" if sec else field
                raise InputError(where, "missing (required)")

    d = Description()

    def g(s: str, f: str) -> Any:
        return vals.get((s, f))

    d.name = check_name(g("", "name"))
    d.desc = check_description(g("", "description") or d.name)
    d.board = g("", "board")
    if not NAME_RE.fullmatch(d.board):
        raise InputError("board", f"{d.board[:40]!r}: a board name is lower-case letters, digits and _ "
                                  f"(boards/board_<board>.h)")
    d.pwm_hz = g("", "pwm_frequency")
    d.pole_pairs = g("motor", "pole_pairs")
    d.r_ph = g("motor", "resistance") * g("motor", "resistance_kind")
    d.l_ph = g("motor", "inductance") * g("motor", "inductance_kind")
    d.ke_ll = g("motor", "back_emf") * g("motor", "back_emf_kind")
    ck = g("motor", "current_kind")
    d.i_rated = g("motor", "rated_current") * ck
    d.n_rated = g("motor", "rated_speed")
    d.i_peak = g("motor", "peak_current")
    if d.i_peak is not None:
        d.i_peak *= ck
    d.j = g("motor", "inertia")
    d.n_max = g("application", "max_speed")
    d.n_min = g("application", "min_speed")
    d.wc = g("application", "current_bandwidth")
    d.i_fw_load = g("application", "fw_load_current")
    d.t_start = g("application", "start_load")
    if d.i_fw_load is not None:
        d.i_fw_load *= ck

    # physical sanity, each naming its field
    if not 1 <= d.pole_pairs <= 32:
        raise InputError("motor.pole_pairs", f"{d.pole_pairs}: must be 1..32")
    positive: list[tuple[str, float | None]] = [
        ("motor.resistance", d.r_ph), ("motor.inductance", d.l_ph), ("motor.back_emf", d.ke_ll),
        ("motor.rated_current", d.i_rated), ("motor.rated_speed", d.n_rated),
        ("motor.peak_current", d.i_peak), ("motor.inertia", d.j),
        ("application.max_speed", d.n_max), ("application.min_speed", d.n_min),
        ("application.current_bandwidth", d.wc), ("application.fw_load_current", d.i_fw_load),
        ("application.start_load", d.t_start)]
    for name, x in positive + [("pwm_frequency", d.pwm_hz)]:
        if x is not None and not x > 0.0:
            raise InputError(name, f"must be > 0 (got {x:g})")
        lo, hi, unit = PLAUSIBLE[name]
        if x is not None and not lo <= x <= hi:
            raise InputError(name, f"{x:g} {unit} is outside {lo:g} .. {hi:g} {unit}, what a motor this "
                                   f"firmware drives could have (a unit slip?)")
    if d.pwm_hz is not None and abs(d.pwm_hz - round(d.pwm_hz)) > 1e-6:
        raise InputError("pwm_frequency", "must be a whole number of Hz")
    if d.i_peak is not None and d.i_peak < d.i_rated:
        raise InputError("motor.peak_current", f"{d.i_peak:g} A is below the rated current {d.i_rated:g} A")
    if d.n_min is not None and d.n_min >= d.n_rated and (d.n_max is None or d.n_min >= d.n_max):
        raise InputError("application.min_speed", "must be below the top speed")
    if TUNING_SECTION in data:
        d.tuning = parse_tuning(data[TUNING_SECTION], reasons or {})
    d.raw = vals
    _inertia_check(d, given.get(("motor", "inertia")))
    return d
