"""The motor description file (TOML): fields, units, validation.

    name = "hurst075"            # profile name: firmware/motors/motor_<name>.h
    description = "..."          # optional, becomes MOTOR_NAME
    board = "mclv"               # firmware/boards/board_<board>.h
    pwm_frequency = "20 kHz"     # optional (UserParms.h default otherwise)

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
2.67"). Every problem raises InputError naming the field.
"""

import difflib
import math
import re
import tomllib

from . import units
from .units import InputError

SQRT2 = math.sqrt(2.0)
SQRT3 = math.sqrt(3.0)

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


class Description:
    """Validated motor description, SI units (speeds in rpm, Ke in V/krpm peak line-to-line,
    currents A peak, R and L per phase)."""

    def __init__(self):
        self.source = ""
        self.name = self.desc = self.board = None
        self.pwm_hz = None
        self.pole_pairs = 0
        self.r_ph = self.l_ph = self.ke_ll = self.i_rated = self.n_rated = 0.0
        self.i_peak = self.j = self.n_max = self.n_min = self.wc = self.i_fw_load = None
        self.raw = {}


def _match_key(section, key, fields):
    """Canonical field of a key, allowing a unit suffix (resistance_ohm)."""
    if key in fields:
        return key, key
    for f, (q, _) in fields.items():
        if q in units._SUFFIX_UNITS and units.base_key(key, q) == f and key != f:
            return f, key
    where = f"{section}.{key}" if section else key
    close = difflib.get_close_matches(key, list(fields), n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]}?)" if close else f" (known: {', '.join(fields)})"
    raise InputError(where, f"unknown field{hint}")


def _read_kind(field, value, kind):
    if not isinstance(value, str):
        raise InputError(field, f"expected one of {', '.join(KINDS[kind])}")
    v = value.strip().lower()
    v = _KIND_ALIASES.get(v, v)
    if kind == "kind_emf":
        v = v.replace("line to line", "line-to-line").replace(" ll", " line-to-line")
    if v not in KINDS[kind]:
        raise InputError(field, f"{value!r} is not one of: {', '.join(KINDS[kind])}")
    return KINDS[kind][v]


def load(path):
    try:
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except FileNotFoundError:
        raise InputError("file", f"{path}: no such file") from None
    except tomllib.TOMLDecodeError as e:
        raise InputError("file", f"{path}: not valid TOML ({e})") from None
    d = parse(data)
    d.source = path
    return d


def parse(data):
    vals = {}
    for sec, fields in SECTIONS.items():
        table = data if sec == "" else data.get(sec, {})
        if sec and not isinstance(table, dict):
            raise InputError(sec, "must be a [section]")
        for key, value in table.items():
            if sec == "" and key in SECTIONS and isinstance(value, dict):
                continue
            field, k = _match_key(sec, key, fields)
            where = f"{sec}.{key}" if sec else key
            qty = fields[field][0]
            if (sec, field) in vals:
                raise InputError(where, "given twice (with and without a unit suffix)")
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
        for field, (_, required) in fields.items():
            if required and (sec, field) not in vals:
                where = f"{sec}.{field}" if sec else field
                raise InputError(where, "missing (required)")

    d = Description()
    g = lambda s, f: vals.get((s, f))  # noqa: E731
    d.name = g("", "name")
    if not re.fullmatch(r"[a-z][a-z0-9_]*", d.name):
        raise InputError("name", f"{d.name!r}: use lower-case letters, digits and _ (it becomes motor_<name>.h)")
    d.desc = g("", "description") or d.name
    if '"' in d.desc or "\\" in d.desc or "*/" in d.desc:
        raise InputError("description", "must not contain quotes, backslashes or */")
    d.board = g("", "board")
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
    positive = [("motor.resistance", d.r_ph), ("motor.inductance", d.l_ph), ("motor.back_emf", d.ke_ll),
                ("motor.rated_current", d.i_rated), ("motor.rated_speed", d.n_rated),
                ("motor.peak_current", d.i_peak), ("motor.inertia", d.j),
                ("application.max_speed", d.n_max), ("application.min_speed", d.n_min),
                ("application.current_bandwidth", d.wc), ("application.fw_load_current", d.i_fw_load),
                ("application.start_load", d.t_start)]
    for field, v in positive:
        if v is not None and not v > 0.0:
            raise InputError(field, f"must be > 0 (got {v:g})")
    if d.pwm_hz is not None and abs(d.pwm_hz - round(d.pwm_hz)) > 1e-6:
        raise InputError("pwm_frequency", "must be a whole number of Hz")
    if d.i_peak is not None and d.i_peak < d.i_rated:
        raise InputError("motor.peak_current", f"{d.i_peak:g} A is below the rated current {d.i_rated:g} A")
    if d.n_min is not None and d.n_min >= d.n_rated and (d.n_max is None or d.n_min >= d.n_max):
        raise InputError("application.min_speed", "must be below the top speed")
    d.raw = vals
    return d
