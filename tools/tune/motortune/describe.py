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
    d = parse(loads(safeio.read_utf8(path, "file", MAX_TOML_BYTES)))
    d.source = path
    return d


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


def parse(data: dict[str, Any]) -> Description:
    if not isinstance(data, dict):
        raise InputError("file", "not a TOML table")
    vals: dict[tuple[str, str], Any] = {}
    given: dict[tuple[str, str], Any] = {}  # the values as written, for hints
    for sec, fields in SECTIONS.items():
        table = data if sec == "" else data.get(sec, {})
        if sec and not isinstance(table, dict):
            raise InputError(sec, "must be a [section]")
        for key, value in table.items():
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
    d.raw = vals
    _inertia_check(d, given.get(("motor", "inertia")))
    return d
