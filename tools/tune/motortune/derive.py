# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""From a motor description to every value of a motor profile, with the reason for each.

All arithmetic in SI units (speeds in rpm where named so). Phase quantities
are per phase; currents and voltages are peak amplitudes of the phase
sinusoid (the core's scales). The voltage limit is the one the core applies
(MC_VOLTAGE_LIMIT_FRACTION of the SVGen full scale Vbus/sqrt 3) less a
headroom for the current loops and the dead time.

The board, UserParms.h and the ranges the core holds each value to come from
the core's headers through the probe (probe.board): nothing here restates a
constant of the core. `derive` runs the steps below in order; each reads the
motor data and what the steps before it chose (Tuning), and adds its values
(Value: macro, number, unit, reason) for the header writer.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass, field

from . import probe
from .describe import Description
from .units import RPM, SQRT3, TWO_PI, InputError

SPEED_PM_DEG = 40.0  # the speed loop's phase margin at the lightest claimed rotor
SPEED_ZERO_RATIO = 8.0  # the speed PI's zero at the crossover / this
SPEED_J_MIN_SCALE = 0.5  # the lightest rotor the profile claims, x the stated inertia (make robust draws 0.5..20)
START_LOAD_SHARE = 0.6  # the start load's share of the forced current's torque Kt I_ramp
OL_DAMP_ZETA = 0.35  # open-loop damping ratio MOTOR_OL_DAMP_S is computed for (UserParms.h: why low)
CURRENT_PM_DEG = 70.0  # the current loops' phase margin with their 1.5-period delay
# The fewest counts a PI gain may have in the core's Q15 form: at 16 counts rounding alone
# moves it by up to 3 %; at 0 the loop does nothing. Fewer is a unit slip upstream (the
# shipped examples have 392 or more). Judged on the integers the probe reads (cli.py).
MIN_GAIN_COUNTS = 16
GAIN_MARGIN = 0.9  # a gain the tool lowers to fit the core's range stays this far inside it
SPEED_KP_MARGIN = 0.78125  # ... the speed Kp this far (100 of the core's 128)
FS_STEP_MARGIN = 0.95  # the speed scale's angle step 2 pi omega_fs Ts stays this far below 1


class Infeasible(Exception):
    """The request cannot be met on this board: the message starts with the field."""

    def __init__(self, field_name: str, message: str) -> None:
        super().__init__(f"{field_name}: {message}")
        self.field = field_name


@dataclass
class Value:
    macro: str
    number: float
    unit: str
    reason: str
    fmt: str = "{:.4g}"
    text: str | None = None  # the C text as given ([tuning]), instead of fmt


def fmt_num(x: float, fmt: str = "{:.4g}") -> str:
    s = fmt.format(x)
    if "e" not in s and "." not in s and "inf" not in s and "nan" not in s:
        s += ".0"
    return s


def sig(x: float, n: int = 4) -> float:
    """x rounded to n significant digits (what the header prints)."""
    if x == 0:
        return 0.0
    return float(f"{x:.{n}g}")


def sig_down(x: float, n: int = 3) -> float:
    """x rounded down to n significant digits (limits never round up)."""
    if x <= 0:
        return 0.0
    e = math.floor(math.log10(x)) - (n - 1)
    return float(f"{math.floor(x / 10.0**e + 1e-9)}e{e}")


def sig_up(x: float, n: int = 3) -> float:
    """x rounded up to n significant digits: a value the core bounds from below (the lock
    current's dead-time bands) never rounds under its bound."""
    if x <= 0:
        return 0.0
    e = math.floor(math.log10(x)) - (n - 1)
    return float(f"{math.ceil(x / 10.0**e - 1e-9)}e{e}")


def round_up(x: float, step: float) -> float:
    return math.ceil(x / step - 1e-9) * step


def round_down(x: float, step: float) -> float:
    return math.floor(x / step + 1e-9) * step


@dataclass(frozen=True)
class GainBlame:
    """The description field a gain's trouble is reported against, and a hint."""

    field: str
    hint: str


@dataclass
class Tuning:
    """Every derived value (.values, in the header's order) and what the steps share."""

    desc: Description
    board: probe.Board
    values: list[Value] = field(default_factory=list)
    by: dict[str, Value] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)  # the header's introduction
    warnings: list[str] = field(default_factory=list)  # derating: printed, and in the header
    limited: list[str] = field(default_factory=list)  # values held to the core's ranges: printed, and in the header
    gains: dict[str, GainBlame] = field(default_factory=dict)  # each PI gain: whom its trouble names
    fw_table: list[float] = field(default_factory=list)
    fw_speeds: list[float] = field(default_factory=list)
    tuned: dict[str, str] = field(default_factory=dict)  # [tuning]: macro -> the header comment (generate.py)
    # the motor and the choices the steps share (SI units; speeds rpm)
    psi: float = 0.0  # V s/rad electrical (Wb)
    kt: float = 0.0  # N m per A peak
    e_per_rpm: float = 0.0  # phase peak volts per rpm
    v_ss: float = 0.0  # steady-state voltage budget, phase peak
    dt_frac: float = 0.0  # dead time x fpwm
    i_peak: float = 0.0
    i_qmax: float = 0.0
    trip: float = 0.0
    i_load: float = 0.0
    n_bus: float = 0.0
    n_nom: float = 0.0
    n_fw: float = 0.0
    n_min: float = 0.0
    id_limit: float = 0.0
    top_field: str = ""
    speed_fs: float = 0.0
    i_lock: float = 0.0
    i_ramp: float = 0.0
    spd_fc: float = 0.0
    wc: float = 0.0

    @property
    def fpwm(self) -> int:
        return self.board.fpwm

    @property
    def i_fs(self) -> float:
        return self.board.i_fs

    def add(self, macro: str, number: float, unit: str, reason: str, fmt: str = "{:.4g}") -> float:
        v = Value(macro, number, unit, reason, fmt)
        self.values.append(v)
        self.by[macro] = v
        return number

    def __getitem__(self, macro: str) -> float:
        return self.by[macro].number

    def held(self, macro: str, value: float, lo: float, hi: float, why: str) -> float:
        """value held to [lo, hi], the core's range for macro (why: where it is checked); a
        value that had to move is noted, so the user learns the rule did not give it."""
        if lo <= value <= hi:
            return value
        held = lo if value < lo else hi
        self.limited.append(f"{macro} {value:.4g} held to {held:.4g}: {why}")
        return held


# ---- models ------------------------------------------------------------------------------


def bisect_last(pred: Callable[[float], bool], lo: float, hi: float, steps: int) -> float:
    """Narrows [lo, hi] with pred(lo) true and pred(hi) false for `steps` halvings;
    returns the last point known true."""
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        if pred(mid):
            lo = mid
        else:
            hi = mid
    return lo


def speed_margin(w: float, ws: float, zr: float, fc: float, loop_hz: float) -> float:
    """Phase margin (deg) of the speed loop crossing over at w (rad/s) when it was designed for
    ws: the PI zero at ws / zr; the speed filter as the core runs it, y += a (x - y) once a loop
    period T with a = 2 pi fc T; a delay of 1.5 T (the window's mean age, the hold of the Iq
    reference, the current loop)."""
    t = 1.0 / loop_hz
    a = TWO_PI * fc * t
    filt = a / (1.0 - (1.0 - a) * cmath.exp(-1j * w * t))
    return 90.0 - math.degrees(math.atan(ws / zr / w) - cmath.phase(filt) + 1.5 * w * t)


def speed_crossover(pm_deg: float, k: float, zr: float, fc: float, loop_hz: float) -> float:
    """The design crossover ws (rad/s) whose loop, crossing over at k x ws (a rotor of 1/k times
    the inertia), keeps pm_deg of phase margin there (the margin falls as w rises)."""
    return bisect_last(lambda ws: speed_margin(k * ws, ws, zr, fc, loop_hz) >= pm_deg, 1.0, 1e5, 60)


def id_for_voltage(w: float, r: float, l: float, psi: float, iq: float, vmax: float) -> float | None:
    """Smallest |Id| (Id <= 0) with |V| <= vmax in steady state at electrical speed w:
    Vd = R Id - w L Iq, Vq = R Iq + w (psi + L Id). None when no Id reaches it.
    |V|^2 - vmax^2 = A Id^2 + B Id + C, a quadratic in Id."""
    a_ = w * l * iq
    b_ = r * iq + w * psi
    qa = r * r + (w * l) ** 2
    qb = 2.0 * (b_ * w * l - r * a_)
    qc = a_ * a_ + b_ * b_ - vmax * vmax
    if qc <= 0.0:
        return 0.0
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return None
    return min(0.0, (-qb + math.sqrt(disc)) / (2.0 * qa))


def voltage_at(t: Tuning, n: float, i_d: float, i_q: float) -> float:
    """Steady-state phase voltage at n rpm with (Id, Iq)."""
    d = t.desc
    w = n * RPM * d.pole_pairs
    return math.hypot(d.r_ph * i_d - w * d.l_ph * i_q, d.r_ph * i_q + w * (t.psi + d.l_ph * i_d))


def id_needed(t: Tuning, n: float) -> float | None:
    d = t.desc
    return id_for_voltage(n * RPM * d.pole_pairs, d.r_ph, d.l_ph, t.psi, t.i_load, t.v_ss)


# ---- the steps ---------------------------------------------------------------------------


def board_for(desc: Description) -> probe.Board:
    """The board at the description's PWM frequency; the core's refusal of that frequency
    (its checks of the board and the PWM alone) names pwm_frequency."""
    fpwm = round(desc.pwm_hz) if desc.pwm_hz is not None else None
    try:
        return probe.board(desc.board, fpwm)
    except probe.CoreRefusal as e:
        if fpwm is None:
            raise InputError("board", f"the core refuses boards/board_{desc.board}.h: {e.refusals[0].line()}") from None
        raise InputError("pwm_frequency", f"{fpwm} Hz: the core refuses it: {e.refusals[0].line()}") from None


# The description's field of each electrical value the core checks on its own.
MOTOR_FIELDS = {"MOTOR_POLE_PAIRS": "motor.pole_pairs", "MOTOR_RS_OHM": "motor.resistance",
                "MOTOR_LS_H": "motor.inductance", "MOTOR_KE_VPK_LL_PER_KRPM": "motor.back_emf"}


def motor_constants(t: Tuning) -> None:
    """The motor's constants, once its electrical data passes the core's checks of them
    alone (R, L and Ke against the board's scales and the PWM: mc_derived.h "motor model")."""
    d = t.desc
    ripple_band(t)  # a small L: the dead-time band first, in the terms of the description
    given = {"MOTOR_POLE_PAIRS": d.pole_pairs, "MOTOR_RS_OHM": d.r_ph, "MOTOR_LS_H": d.l_ph,
             "MOTOR_KE_VPK_LL_PER_KRPM": d.ke_ll}
    failed = [r for r in probe.partial_refusals(t.board, {k: float(v) if k != "MOTOR_POLE_PAIRS" else v
                                                          for k, v in given.items()})
              if r.param in given]  # not UserParms.h defaults computed from them: derive sets those
    if failed:
        r = failed[0]
        field_name = MOTOR_FIELDS.get(r.param, r.param)
        raise Infeasible(field_name, f"{r.param} = {given.get(r.param, 0):g}: the core refuses it: {r.line()}")
    t.psi = d.ke_ll / SQRT3 / (1000.0 * RPM * d.pole_pairs)
    t.kt = 1.5 * d.pole_pairs * t.psi
    t.e_per_rpm = d.ke_ll / SQRT3 / 1000.0


def voltage_budget(t: Tuning) -> None:
    """The shunt window keeps the measured phases' duties at or below MC_DUTY_SAMPLE_MAX
    (mc_derived.h), so no line-to-line duty difference involving them exceeds it: a circle
    wider than that fraction is not available in every sector."""
    b = t.board
    td = b.deadtime_ns * 1e-9
    t.dt_frac = td * b.fpwm
    headroom = 1.0 - 0.05 - t.dt_frac
    win = b.duty_sample_max / b.duty_max
    vfrac = b.vlim_fraction
    vfrac_ss = min(vfrac, win)
    t.v_ss = vfrac_ss * b.v_fs * headroom
    if vfrac_ss < vfrac:
        limit = (f"{vfrac_ss:.3f} (the shunt window: the measured phases' duties stay at or below "
                 f"{100 * win:.1f} %, MC_DUTY_SAMPLE_MAX; MC_VOLTAGE_LIMIT_FRACTION is {vfrac:g})")
    else:
        limit = f"{vfrac:g} (MC_VOLTAGE_LIMIT_FRACTION)"
    t.notes.append(
        f"Steady-state voltage budget: {limit} x {b.vbus:g} V / sqrt 3 = {vfrac_ss * b.v_fs:.2f} V phase peak, "
        f"times {headroom:.2f} (5 % left to the current loops, {100 * t.dt_frac:.0f} % = dead time "
        f"{td * 1e6:g} us x {b.fpwm} Hz) = {t.v_ss:.2f} V.")


def currents(t: Tuning) -> None:
    """The trip and the Iq limit from the motor's currents and the board's scale."""
    d, b = t.desc, t.board
    # 90 % of the scale, and no more than both polarities reach with an offset (MC_TRIP_REACH_A)
    trip_board = min(0.9 * b.i_fs, sig_down(b.trip_reach, 3))
    i_peak_req = d.i_peak if d.i_peak is not None else d.i_rated
    t.trip = min(trip_board, 1.25 * i_peak_req)
    i_total = 0.9 * t.trip  # what mc.c lets |(Id, Iq)| reach (MC_I_TOTAL)
    derated = i_total < i_peak_req - 1e-9
    t.i_peak = min(i_peak_req, i_total)
    i_qmax = min(d.i_rated, t.i_peak)
    msg = ""
    if derated:
        msg = (f"derated: the {b.name} reads +-{b.i_fs:g} A, the trip must stay at or below {trip_board:.2f} A "
               f"(90 % of it, and what both polarities reach with an offset) and the core holds |I| to 90 % "
               f"of the trip, so the motor's "
               f"{i_peak_req:.3g} A peak is limited to {t.i_peak:.3g} A ({100 * t.i_peak / i_peak_req:.0f} % of its "
               f"torque)")
        t.warnings.append(msg)
    t.add("MOTOR_OVERCURRENT_A", sig(t.trip, 3), "A",
          f"software trip: min(90 % of the {b.i_fs:g} A current full scale, so one sample of overshoot still "
          f"reads inside the ADC range, and the {b.trip_reach:.3g} A both polarities reach with the largest "
          f"offset calibration accepts: {trip_board:.3g} A; 1.25 x the peak current {i_peak_req:.3g} A)")
    t.add("MOTOR_CURRENT_MAX_A", sig_down(i_qmax, 3), "A",
          f"|Iq| limit of the speed loop: the rated {d.i_rated:.3g} A peak" +
          (f", {msg}" if derated else " (continuous torque)"))
    t.i_qmax = t["MOTOR_CURRENT_MAX_A"]


def speeds(t: Tuning) -> None:
    """Nominal and top speed. The load current the voltage budget is computed for: the
    field-weakening table and the nominal speed are exact at this Iq (more load at the same
    speed asks for more voltage; the current loops' 5 % headroom covers some)."""
    d, b = t.desc, t.board
    t.i_load = d.i_fw_load if d.i_fw_load is not None else 0.25 * t.i_qmax
    if t.i_load > t.i_qmax:
        raise Infeasible("application.fw_load_current", f"{t.i_load:.3g} A exceeds the Iq limit {t.i_qmax:.3g} A")

    def inside_at_id0(n: float) -> bool:  # nominal speed: the highest with Id = 0 inside the budget
        return voltage_at(t, n, 0.0, t.i_load) < t.v_ss

    hi = 1.0
    while inside_at_id0(hi) and hi < 1e7:
        hi *= 2.0
    t.n_bus = bisect_last(inside_at_id0, 0.0, hi, 80)
    n_top = d.n_max if d.n_max is not None else d.n_rated
    t.top_field = "application.max_speed" if d.n_max is not None else "motor.rated_speed"
    # Id limit: the total current may reach i_peak (|(Id, Iq_load)| <= i_peak).
    t.id_limit = max(-math.sqrt(max(t.i_peak * t.i_peak - t.i_load * t.i_load, 0.0)), -0.95 * b.i_fs)

    if n_top <= t.n_bus:
        t.n_nom = round_down(n_top, 10.0)
        t.n_fw = t.n_nom
        fw_reason = (f"= the top speed {n_top:.0f} rpm ({t.top_field}): the bus reaches {t.n_bus:.0f} rpm without "
                     f"field weakening at Iq = {t.i_load:.2g} A, so none is needed (AN1078: nominal = FW max disables "
                     f"it)")
    else:
        def reachable(n: float) -> bool:  # with Id inside the current limit
            i_d = id_needed(t, n)
            return i_d is not None and i_d >= t.id_limit

        if not reachable(n_top):
            lo = bisect_last(reachable, t.n_bus, n_top, 60)
            raise Infeasible(
                t.top_field,
                f"{n_top:.0f} rpm is beyond the {b.vbus:g} V bus even with field weakening: at most "
                f"{round_down(lo, 10):.0f} rpm with |I| <= {t.i_peak:.3g} A (Id >= {t.id_limit:.2f} A at Iq = "
                f"{t.i_load:.2g} A; raise motor.peak_current or lower the speed)")
        t.n_nom = round_down(t.n_bus, 10.0)
        t.n_fw = n_top
        fw_reason = (f"highest speed with Id = 0: back-EMF {t.e_per_rpm * 1000:.3f} V/krpm phase peak plus the R and "
                     f"wL drops at Iq = {t.i_load:.2g} A reach the {t.v_ss:.2f} V budget at {t.n_bus:.0f} rpm")
    t.add("MOTOR_SPEED_NOMINAL_RPM", t.n_nom, "rpm", fw_reason, "{:.1f}")
    t.add("MOTOR_SPEED_FW_MAX_RPM", t.n_fw, "rpm",
          f"top speed asked for ({t.top_field})" + ("" if t.n_fw > t.n_nom else ", no field weakening"), "{:.1f}")


def field_weakening_table(t: Tuning) -> None:
    """16 points of Id from nominal to FW max."""
    tab: list[float] = []
    spd: list[float] = []
    for k in range(16):
        n = t.n_nom + (t.n_fw - t.n_nom) * k / 15.0
        i_d = 0.0 if (k == 0 or t.n_fw <= t.n_nom) else id_needed(t, n)
        if i_d is None or i_d < t.id_limit - 1e-9:
            raise Infeasible(t.top_field, f"field weakening fails at {n:.0f} rpm")  # guarded in speeds()
        tab.append(round(i_d, 3) + 0.0)
        spd.append(n)
    for k in range(1, 16):  # rounding must not break monotony
        tab[k] = min(tab[k], tab[k - 1])
    t.fw_table, t.fw_speeds = tab, spd


def speed_scale(t: Tuning) -> None:
    """Speed full scale: 1.5 x the top speed, a round 1000 rpm, inside the core's ranges."""
    b, pp = t.board, t.desc.pole_pairs
    fs = round_up(1.5 * t.n_fw, 1000.0)
    fs_max = min(b.fpwm * 60.0 / (TWO_PI * pp) * FS_STEP_MARGIN,  # the angle step 2 pi omega_fs Ts < 1
                 32767.0 * b.speed_ramp_rpm_s / b.loop_hz)  # the reference's slew >= 1 count
    # The stall detector's speed error is a fixed number of rpm (UserParms.h) the core wants
    # inside the speed scale: a slow motor (top speed under 1000 rpm) gets a wider scale.
    stall_err = b.stall_speed_error_rpm
    fs = t.held("MOTOR_SPEED_FULLSCALE_RPM", fs, round_up(stall_err + 1.0, 1000.0), math.inf,
                f"above MC_STALL_SPEED_ERROR_RPM = {stall_err:g} rpm (mc_derived.h "
                f"MC_CHECK_FOR(MC_STALL_SPEED_ERROR_RPM, MC_SPEED_FULLSCALE_RPM))")
    fs = min(fs, round_down(fs_max, 100.0))
    if fs < t.n_fw / b.limits.speed_fs_top_fraction:
        raise Infeasible(t.top_field, f"{t.n_fw:.0f} rpm x {pp} pole pairs is too fast for {b.fpwm} Hz PWM "
                         f"(speed full scale would have to exceed {fs_max:.0f} rpm); raise pwm_frequency")
    if fs <= stall_err:
        raise Infeasible("pwm_frequency", f"{b.fpwm} Hz with {pp} pole pairs limits the speed scale to "
                         f"{fs_max:.0f} rpm, not above the stall detector's {stall_err:g} rpm "
                         f"(MC_STALL_SPEED_ERROR_RPM)")
    t.speed_fs = fs
    t.add("MOTOR_SPEED_FULLSCALE_RPM", fs, "rpm",
          "Q15 full scale of every speed: 1.5 x the top speed rounded up to 1000 rpm (room for overshoot, "
          "core check FW max <= 0.95 x full scale)", "{:.1f}")


def min_speed(t: Tuning) -> None:
    """Lowest closed-loop speed: the estimator needs a back-EMF well above the voltage error
    of the dead time (square wave, fundamental 4/pi x 2/3 x Td fpwm Vbus), which the core
    compensates only approximately."""
    d = t.desc
    v_dt = 4.0 / math.pi * 2.0 / 3.0 * t.dt_frac * t.board.vbus
    n_emf = 3.0 * v_dt / t.e_per_rpm
    t.n_min = d.n_min if d.n_min is not None else round_up(max(n_emf, 0.08 * t.n_fw), 50.0)
    if t.n_min >= t.n_nom:
        raise Infeasible("application.min_speed" if d.n_min is not None else t.top_field,
                         f"lowest closed-loop speed {t.n_min:.0f} rpm is not below the nominal {t.n_nom:.0f} rpm")
    t.add("MOTOR_SPEED_MIN_RPM", t.n_min, "rpm",
          ("given (application.min_speed)" if d.n_min is not None else
           f"max(back-EMF = 3 x the dead-time voltage error {v_dt:.2f} V -> {n_emf:.0f} rpm, 8 % of the top "
           f"speed), rounded up to 50 rpm; the estimator's filter floor (MC_ESTIMATOR_MIN_RPM) is 0.8 x the "
           f"ramp end"), "{:.1f}")


def ripple_band(t: Tuning) -> float:
    """UserParms.h's default dead-time band, Vbus / (12 L fpwm), the phase current's ripple;
    the core wants it below a fraction of I_FS: an L so small that the ripple reaches it is
    refused."""
    b = t.board
    band = b.vbus / (12.0 * t.desc.l_ph * b.fpwm)
    top = b.limits.deadtime_band_max_fraction
    if band >= top * b.i_fs:
        raise Infeasible("motor.inductance", f"the current ripple Vbus / (12 L fpwm) = {band:.3g} A is {top:g} of "
                         f"the {b.i_fs:g} A current scale or more (MC_DEADTIME_BAND_A < {top:g} I_FS): L is too small "
                         f"for this board at {b.fpwm} Hz")
    return band


def dead_time_band(t: Tuning) -> float:
    """The dead-time compensation's band (A): the ripple (ripple_band). The core
    (mc_derived.h MC_CHECK_FOR(MC_DEADTIME_BAND_A, MOTOR_LS_H)) wants it, in Q15 counts of
    current, above the dead time's counts (the in-band slope < 1): a large L (15 mH at 20 kHz
    on the MCLV) gets the narrowest band it allows, written into the profile (a wider band
    under-compensates a little; UserParms.h)."""
    b, l = t.board, t.desc.l_ph
    band = ripple_band(t)
    counts = b.dt_counts
    band_min = sig_up((counts + 1.5) * b.i_fs / 32768.0, 3)  # Q15 counts of the band > MC_DT_COUNTS, rounding kept
    if band < band_min:
        band = t.held("MC_DEADTIME_BAND_A", band, band_min, math.inf,
                      f"above the {counts} dead-time counts in Q15 of the current scale (mc_derived.h "
                      f"MC_CHECK_FOR(MC_DEADTIME_BAND_A, MOTOR_LS_H): the in-band slope < 1)")
        t.add("MC_DEADTIME_BAND_A", band, "A",
              f"dead-time compensation band (UserParms.h): the ripple Vbus / (12 L fpwm) = "
              f"{b.vbus / (12.0 * l * b.fpwm):.3g} A is narrower than the core can represent against {counts} "
              f"dead-time counts: the narrowest it allows")
    return band


def start_current(t: Tuning) -> float:
    """The lock current (t.i_lock) and the start load it is sized for (returned). The load
    must take at most START_LOAD_SHARE of the forced current's torque Kt I, so the rotor
    runs at a load angle of at most 37 deg behind the forced angle (the ramp's acceleration
    takes 20 % more) and a plant with 15 % less back-EMF constant still starts. The
    firmware measures the inverter's dead time at the lock (mc.c note 4,
    MC_DEADTIME_MEASURE): the lock current must be MC_DTM_LOCK_BANDS dead-time bands at
    least, which mc_derived.h checks."""
    d, kt, i_qmax = t.desc, t.kt, t.i_qmax
    i_default = sig(min(0.6 * d.i_rated, 0.6 * i_qmax), 3)
    if d.t_start is not None:
        i_need = d.t_start / (START_LOAD_SHARE * kt)
        if i_need > i_qmax:
            raise Infeasible("application.start_load",
                             f"{d.t_start:g} N m needs {i_need:.3g} A of start-up current (the load at most "
                             f"{START_LOAD_SHARE:.0%} of Kt I, Kt = {kt * 1000:.2f} mN m/A), above the Iq limit "
                             f"{i_qmax:.3g} A: the motor cannot start this load")
        # rounded up, less 0.05 %: the 60 % share is the tool's margin, not a limit of the core
        i_lock = max(i_default, sig_up(i_need / 1.0005, 3))
        lock_reason = (f"the start load {d.t_start * 1000:.3g} mN m at {START_LOAD_SHARE:.0%} of Kt I "
                       f"(Kt = {kt * 1000:.2f} mN m/A) -> {i_need:.3g} A, at least 0.6 x the continuous current "
                       f"{min(d.i_rated, i_qmax):.3g} A: the lock pulls the rotor against the same load")
        t_start = d.t_start
    else:
        i_lock = i_default
        lock_reason = (f"0.6 x the continuous current {min(d.i_rated, i_qmax):.3g} A: pulls the rotor to the lock "
                       f"angle against cogging and friction (AN1078 INITIALTORQUE 1.0 A for the 1.64 A Hurst); no "
                       f"start load given, so the start is sized for {START_LOAD_SHARE:.0%} of Kt x that")
        t_start = START_LOAD_SHARE * kt * i_lock
    bands = t.board.limits.dtm_lock_bands
    band_dt = dead_time_band(t)
    i_dtm = bands * band_dt
    if i_lock < i_dtm:
        if i_dtm > i_qmax:
            raise Infeasible("motor.inductance",
                             f"measuring the dead time at the lock needs {i_dtm:.3g} A of lock current "
                             f"({bands:.2f} x the dead-time band {band_dt:.3g} A), above the Iq limit "
                             f"{i_qmax:.3g} A: L is too small for this bus (or build with MC_DEADTIME_MEASURE 0)")
        i_lock = sig_up(i_dtm, 3)
        lock_reason += (f"; raised to {i_lock:.3g} A, {bands:.2f} dead-time bands (MC_DEADTIME_BAND_A = "
                        f"{band_dt:.3g} A), the least the lock's dead-time measurement needs")
    t.i_lock = i_lock
    t.add("MOTOR_LOCK_CURRENT_A", i_lock, "A", lock_reason)
    return t_start


def start_up(t: Tuning) -> None:
    """Lock, ramp and open-loop damping."""
    d, b, kt, pp = t.desc, t.board, t.kt, t.desc.pole_pairs
    lim = b.limits
    t_start = start_current(t)
    i_lock, j = t.i_lock, d.j
    if j is not None:
        wn = math.sqrt(pp * kt * i_lock / j)  # rotor swing in the lock torque spring, rad/s
        t_lock = min(max(round_up(8.0 * TWO_PI / wn, 0.01), 0.1), 2.0)
        # the core counts the lock in a uint16_t of periods (2 s is 80000 at 40 kHz)
        t_lock = t.held("MOTOR_LOCK_TIME_S", t_lock, 0.0, round_down(lim.lock_periods_max / b.fpwm, 0.01),
                        f"at most {lim.lock_periods_max:.0f} PWM periods (mc_derived.h MC_CHECK(MOTOR_LOCK_TIME_S))")
        t.add("MOTOR_LOCK_TIME_S", t_lock, "s",
              f"8 periods of the rotor's small swing about the lock angle, w = sqrt(p Kt I_lock / J) = {wn:.0f} "
              f"rad/s (Kt = {kt * 1000:.2f} mN m/A, J = {j:.3g} kg m^2), within 0.1..2 s: a rotor that starts "
              f"near the unstable point 180 deg away takes several small-swing periods to fall in (4 periods "
              f"failed a start from 160 deg in the simulator)")
    else:
        t.add("MOTOR_LOCK_TIME_S", 0.25, "s", "no inertia given: AN1078's LOCKTIMEINSEC")
    t.i_ramp = i_ramp = min(i_lock, t.i_qmax)
    n_end = t.n_min
    if j is not None:
        alpha = 0.2 * kt * i_ramp / j  # rad/s^2: 20 % of the ramp torque accelerates J
        t_ramp_acc = n_end * RPM / alpha
        t_ramp = min(max(round_up(t_ramp_acc, 0.05), 1.0), 10.0)
        ramp_reason = (f"constant acceleration {alpha / RPM:.0f} rpm/s up to the ramp end: 20 % of the ramp torque "
                       f"Kt x {i_ramp:.3g} A = {kt * i_ramp * 1000:.1f} mN m accelerates J (the rest is margin for "
                       f"load and the lag of the forced angle) -> {t_ramp_acc:.3f} s; at least 1 s, so the rotor's "
                       f"swing from the lock dies into the ramp and the observer converges before the hand-off "
                       f"(0.5 s lost 1 to 2 of the simulator's 100 random-angle starts under load)")
    else:
        t_ramp = 1.0
        ramp_reason = "no inertia given: 1 s to the ramp end (AN1078 used 5 s with a brake attached)"
    # The forced angle's 32-bit step grows by MC_RAMP_STEP_INC_ = end step / ramp periods each
    # period, at least MC_RAMP_STEP_INC_MIN counts: a low ramp end (1 pole pair, 40 kHz) needs
    # a shorter ramp.
    inc_min = lim.ramp_step_inc_min
    t_ramp_max = round_down(n_end * pp / 60.0 * 4294967296.0 / (inc_min * b.fpwm * b.fpwm), 0.05)
    if t_ramp_max < 100.0 / b.fpwm:  # and at least 100 periods; 9 rpm x pole pairs at 40 kHz still fits
        raise Infeasible("application.min_speed" if d.n_min is not None else t.top_field,
                         f"the open-loop ramp to {n_end:.0f} rpm cannot be 100 PWM periods long with the forced "
                         f"angle's step growing >= {inc_min:.0f} counts a period (mc_derived.h "
                         f"MC_CHECK(MOTOR_RAMP_TIME_S))")
    t_ramp = t.held("MOTOR_RAMP_TIME_S", t_ramp, 0.0, t_ramp_max,
                    f"the forced angle's step must grow by >= {inc_min:.0f} counts a period "
                    f"(mc_derived.h MC_CHECK(MOTOR_RAMP_TIME_S))")
    if j is not None and n_end * RPM / t_ramp > 0.5 * kt * i_ramp / j:
        # the core refuses a ramp whose acceleration needs more than half its torque
        # (mc_derived.h MC_CHECK_FOR(MOTOR_RAMP_TIME_S, MOTOR_INERTIA_KGM2))
        raise Infeasible("motor.inertia", f"{j:.3g} kg m^2: the open-loop ramp to {n_end:.0f} rpm in at most "
                         f"{t_ramp:g} s needs {j * n_end * RPM / t_ramp * 1000:.1f} mN m, more than half the "
                         f"{kt * i_ramp * 1000:.1f} mN m its {i_ramp:.3g} A give (raise the lock current or "
                         f"lower application.min_speed)")
    t.add("MOTOR_RAMP_TIME_S", t_ramp, "s", ramp_reason)
    t.add("MOTOR_RAMP_END_RPM", n_end, "rpm", "hand-off to closed loop at the lowest closed-loop speed", "{:.1f}")
    t.add("MOTOR_RAMP_CURRENT_A", i_ramp, "A", "Iq during the open-loop ramp: the lock current")
    t.add("MOTOR_START_LOAD_NM", sig(t_start, 4), "N m",
          "the load torque the start-up is sized for (data for tools: the robustness campaign draws loads up to it)")
    if j is not None:
        wn_ol = math.sqrt(pp * kt * i_ramp / j)
        lo, hi = 1.0 / lim.ol_damp_counts_per_period, lim.ol_damp_periods_max
        damp = t.held("MOTOR_OL_DAMP_S", sig(2.0 * OL_DAMP_ZETA / wn_ol, 3), sig_up(lo / b.fpwm, 3),
                      sig_down(hi / b.fpwm, 3), f"{lo:g}..{hi:g} PWM periods (mc_derived.h MC_CHECK(MOTOR_OL_DAMP_S))")
        t.add("MOTOR_OL_DAMP_S", damp, "s",
              f"open-loop damping (UserParms.h): zeta {OL_DAMP_ZETA} for the rotor's swing about the forced angle, "
              f"w = sqrt(p Kt I_ramp / J) = {wn_ol:.0f} rad/s: 2 zeta / w")


def observer(t: Tuning) -> None:
    """Kslide, the linear band (dead-beat) and the estimated speed's filter."""
    d, b = t.desc, t.board
    v_fs, ts, r, l = b.v_fs, 1.0 / b.fpwm, d.r_ph, d.l_ph
    vfrac = b.vlim_fraction
    e_top = t.e_per_rpm * t.n_fw
    e_seen = min(e_top, vfrac * v_fs)
    ks = sig(min(1.5 * e_seen, 0.97 * v_fs), 4)
    t.add("MOTOR_SMC_GAIN_V", ks, "V",
          f"Kslide = min(1.5 x the largest back-EMF the observer sees, 97 % of V_FS = {0.97 * v_fs:.3g} V, the "
          f"cap of the hand-tuned profiles; the core allows {b.emf_fs_ratio:g} V_FS, docs/estimator.md wants "
          f"Kslide above that back-EMF); "
          f"that back-EMF is min(Ke at the top speed = {e_top:.3g} V, the voltage limit {vfrac * v_fs:.3g} V: "
          f"above nominal field weakening holds it there)")
    t.spd_fc = b.loop_hz / 10.0
    t.add("MC_SPEED_FILTER_HZ", t.spd_fc, "Hz",
          f"estimated-speed filter cut-off: a tenth of the {b.loop_hz} Hz speed-loop rate (docs/estimator.md: 100 Hz "
          f"at a 1 kHz window converges fastest from a wrong state; the core needs 2 pi fc / loop rate < 1)",
          "{:.1f}")
    f_ex = math.exp(-ts * r / l)
    g_si = (1.0 - f_ex) / r  # A per V per period
    band = sig(ks * g_si / f_ex, 3)
    # The core wants the band below the current scale (mc_derived.h
    # MC_CHECK_FOR(MOTOR_SMC_LINEAR_BAND_A, BOARD_I_FULLSCALE_A)); a small L at a large Ts R/L
    # asks for more. A narrower band only raises the linear band's loop gain c = G Kslide / band
    # above F (smc.h note 3: still linear below 1 + F, relay mode above, which the core allows).
    band_max = sig_down(0.99 * b.i_fs, 3)
    if band > band_max:
        c = ks * g_si / band_max
        mode = f"linear, c < 1 + F = {1.0 + f_ex:.3f}" if c < 1.0 + f_ex else "relay mode, c >= 1 + F (smc.h note 4)"
        band = t.held("MOTOR_SMC_LINEAR_BAND_A", band, 0.0, band_max,
                      f"below the {b.i_fs:g} A current scale (mc_derived.h MC_CHECK_FOR(MOTOR_SMC_LINEAR_BAND_A)); "
                      f"the band's loop gain c = {c:.3f} instead of the dead-beat F = {f_ex:.3f} ({mode})")
    t.add("MOTOR_SMC_LINEAR_BAND_A", band, "A",
          f"MaxSMCError = Kslide G / F (smc.h SMC_MAXERR_DEADBEAT: the linear band's loop gain G Kslide/MaxSMCError "
          f"equals F, a dead-beat correction), G = (1 - F)/R = {g_si:.5f} A/V, F = {f_ex:.5f}")
    if band <= b.i_fs / 32768.0 * 4:
        raise Infeasible("motor.inductance", "the observer's linear band is below 4 LSB of the current scale")


def current_pi(t: Tuning) -> None:
    """The current loops' bandwidth and gains (pole-zero cancellation)."""
    d, b = t.desc, t.board
    ts, r, l, v_fs, i_fs = 1.0 / b.fpwm, d.r_ph, d.l_ph, b.v_fs, b.i_fs
    pm = CURRENT_PM_DEG
    wc_max = math.radians(90.0 - pm) / (1.5 * ts)
    if d.wc is not None:
        wc = d.wc
        wc_reason = f"given (application.current_bandwidth); the delay-limited maximum is {wc_max:.0f} rad/s"
        if wc > wc_max * 1.5:
            raise Infeasible("application.current_bandwidth",
                             f"{wc:.0f} rad/s is beyond what {b.fpwm} Hz sampling allows (1.5 Ts delay: "
                             f"{wc_max:.0f} rad/s for a {pm:.0f} deg phase margin)")
    else:
        # Noise: one ADC count of current (BOARD_ADC_BITS over +-I_FS) times Kp is voltage
        # noise the observer sees as back-EMF; keep it within 2 % of the back-EMF at the
        # lowest closed-loop speed.
        i_count = 2.0 * i_fs / (1 << b.adc_bits)
        wc_noise = 0.02 * t.e_per_rpm * t.n_min / i_count / l
        wc = round_down(min(wc_max, wc_noise), 100.0)
        wc_reason = (f"min(delay: {pm:.0f} deg phase margin with the 1.5 Ts loop delay, (90 - {pm:.0f}) deg / "
                     f"(1.5 Ts) = {wc_max:.0f} rad/s; noise: Kp x one ADC count ({i_count * 1e3:.2f} mA) within "
                     f"2 % of the back-EMF at the lowest closed-loop speed ({t.e_per_rpm * t.n_min:.2f} V), "
                     f"{wc_noise:.0f} rad/s), rounded down to 100 rad/s (in the simulator the delay limit "
                     f"alone, 4600 rad/s, lost the Hurst's 500 rpm operation)")
        # The gains' Q15 ranges (Ki = R wc Ts I_FS / V_FS below the core's MC_KI_MAX: a
        # high-resistance motor on a board with a large current scale): the bandwidth is
        # lowered, the zero still cancels.
        lim = b.limits
        wc_q = GAIN_MARGIN * min(lim.ki_max * v_fs / (i_fs * r * ts), lim.kp_max * v_fs / (i_fs * l))
        if wc_q < wc:
            wc = t.held("MOTOR_CURRENT_LOOP_BW_RAD_S", wc, 0.0, round_down(wc_q, 100.0),
                        f"the current PI's Q15 ranges, Ki Ts I_FS / V_FS < {lim.ki_max:g} and Kp I_FS / V_FS < "
                        f"{lim.kp_max:g} (mc_derived.h MC_CHECK(MOTOR_CURRENT_KI_V_PER_AS))")
            wc_reason += f"; lowered to {wc:.0f} rad/s so the gains fit the core's Q15 ranges"
    t.wc = wc
    t.add("MOTOR_CURRENT_LOOP_BW_RAD_S", wc, "rad/s",
          f"current-loop bandwidth, {wc / TWO_PI:.0f} Hz: {wc_reason}", "{:.1f}")
    t.add("MOTOR_CURRENT_KP_V_PER_A", sig(l * wc, 4), "V/A",
          f"Kp = L wc = {l * 1e3:.4g} mH x wc: pole-zero cancellation (the PI zero Ki/Kp = R/L cancels the "
          f"winding pole, tau = {l / r * 1e3:.3g} ms), leaving a first-order loop of bandwidth wc")
    t.add("MOTOR_CURRENT_KI_V_PER_AS", sig(r * wc, 4), "V/(A s)", f"Ki = R wc = {r:.4g} ohm x wc", "{:.6g}")
    hint = "the current loop could not act; check the value and its unit"
    given = "application.current_bandwidth" if d.wc is not None else ""
    t.gains["MOTOR_CURRENT_KP_V_PER_A"] = GainBlame(given or "motor.inductance", hint)
    t.gains["MOTOR_CURRENT_KI_V_PER_AS"] = GainBlame(given or "motor.resistance", hint)


def speed_pi(t: Tuning) -> None:
    """The speed loop: the Kp schedule's knee, and the gains for the lightest rotor claimed."""
    d, b = t.desc, t.board
    loop_hz, i_fs, fs, kt = b.loop_hz, b.i_fs, t.speed_fs, t.kt
    # Gain schedule of the core (mc.c): Kp is full above MOTOR_SPEED_KP_FULL_RPM and scaled
    # by |speed ref| / that below it (never under MC_SPEED_KP_MIN_FRACTION).
    n_kp_full = min(round_up(3.0 * t.n_min, 100.0), t.n_fw)
    t.add("MOTOR_SPEED_KP_FULL_RPM", n_kp_full, "rpm",
          "speed-PI Kp is full above this speed and reduced below it (the core's gain schedule): 3 x the lowest "
          "closed-loop speed, where the back-EMF is 3 x its smallest usable value and the estimated speed is "
          "clean enough for the full gain (the hand-tuned profiles use the same ratio)", "{:.1f}")
    kp_si_to_rpm = RPM  # A per (rad/s) -> A per rpm
    j = d.j
    capped_by_wc = False
    if j is not None:
        # The crossover is chosen for the lightest rotor the profile claims (SPEED_J_MIN_SCALE of
        # the stated J: the real crossover scales as 1/J): there the phase margin, counting the
        # PI zero (ws/8), the speed filter (the core's one-pole filter run at the loop rate) and
        # the loop's 1.5-period delay, is SPEED_PM_DEG. The sampled-loop rule, loop rate / 20, caps it.
        zr = SPEED_ZERO_RATIO
        ws_pm = speed_crossover(SPEED_PM_DEG, 1.0 / SPEED_J_MIN_SCALE, zr, t.spd_fc, loop_hz)
        ws_cap = TWO_PI * loop_hz / 20.0
        ws = min(ws_pm, ws_cap, t.wc / 8.0)
        # the core's Q15 ranges: Ki / loop * FS / I_FS < MC_KI_MAX and Kp * FS / I_FS < MC_KP_MAX,
        # kept inside them by GAIN_MARGIN and SPEED_KP_MARGIN
        kp_per_ws = j / kt * kp_si_to_rpm  # A/rpm per rad/s of crossover
        lim = b.limits
        ws_q = min(math.sqrt(GAIN_MARGIN * lim.ki_max * zr * loop_hz * i_fs / fs / kp_per_ws),
                   SPEED_KP_MARGIN * lim.kp_max * i_fs / fs / kp_per_ws)
        ws_reason = (f"{SPEED_PM_DEG:.0f} deg of phase margin at {1.0 / SPEED_J_MIN_SCALE:g} x this crossover, "
                     f"where a rotor of {SPEED_J_MIN_SCALE:g} x the stated J puts it")
        if ws_cap < ws_pm:
            ws_reason = f"2 pi x {loop_hz} Hz / 20 = {ws_cap:.0f} rad/s (the sampled-loop cap)"
        if ws_q < ws:
            ws = ws_q
            ws_reason += f", lowered to {ws:.0f} rad/s so Ki fits the core's Q15 range (large J)"
        capped_by_wc = t.wc / 8.0 < min(ws_pm, ws_cap)
        if capped_by_wc:
            ws_reason += f", capped at wc/8 = {t.wc / 8.0:.0f} rad/s (cascade: the current loop 8 x faster)"
        pm_nom = speed_margin(ws, ws, zr, t.spd_fc, loop_hz)
        kp = j * ws / kt
        ki = kp * ws / zr
        t.add("MOTOR_SPEED_KP_A_PER_RPM", sig(kp * kp_si_to_rpm, 3), "A/rpm",
              f"Kp = J ws / Kt with the speed-loop crossover ws = {ws:.0f} rad/s, J = {j:.3g} kg m^2, Kt = 1.5 p psi "
              f"= {kt * 1000:.2f} mN m/A. ws = {ws_reason}; the margin counts the PI zero, the {t.spd_fc:g} Hz "
              f"speed filter and the 1.5-period delay ({pm_nom:.0f} deg at the stated J; docs/tune.md). A "
              f"larger real J lowers the crossover; a smaller one raises it.")
        t.add("MOTOR_SPEED_KI_A_PER_RPM_S", sig(ki * kp_si_to_rpm, 3), "A/(rpm s)",
              f"Ki = Kp ws / {zr:g}: the PI zero {zr:g} x below the crossover, integral action quick enough to "
              f"recover a half-rated load step within 100 ms, slow enough to keep the margin at 20 x the stated J "
              f"(docs/tune.md)")
    else:
        kp_rpm = t.i_qmax / (0.4 * t.n_fw)
        t.add("MOTOR_SPEED_KP_A_PER_RPM", sig(kp_rpm, 3), "A/rpm",
              "no inertia given (safe default): a speed error of 40 % of the top speed asks for the full Iq limit")
        t.add("MOTOR_SPEED_KI_A_PER_RPM_S", sig(kp_rpm * 5.0, 3), "A/(rpm s)",
              "no inertia given (safe default): integral time Kp/Ki = 0.2 s, slow enough for a heavy load")
    # Gains that round to (nearly) 0 in the core are an inertia in the wrong unit (g cm^2 read
    # as kg m^2 gives gains 1e7 times too small): cli.py judges the core's integers.
    blame = (GainBlame("motor.inertia", "the speed loop could not act; did you mean kg cm^2 or g cm^2 for a value "
                                        "written in kg m^2, or the reverse?") if j is not None else
             GainBlame("motor.rated_current", "the speed loop could not act; check the value and its unit"))
    if j is not None and d.wc is not None and capped_by_wc:  # the given current bandwidth set the crossover
        blame = GainBlame("application.current_bandwidth", "the speed loop, 8 x slower than the current loop, "
                                                           "could not act; check the value and its unit")
    t.gains["MOTOR_SPEED_KP_A_PER_RPM"] = blame
    t.gains["MOTOR_SPEED_KI_A_PER_RPM_S"] = blame


STEPS: list[Callable[[Tuning], None]] = [motor_constants, voltage_budget, currents, speeds, field_weakening_table,
                                         speed_scale, min_speed, start_up, observer, current_pi, speed_pi]


def derive(desc: Description) -> Tuning:
    """Every value of the profile for desc, the board read through the probe."""
    t = Tuning(desc, board_for(desc))
    for step in STEPS:
        step(t)
    return t
