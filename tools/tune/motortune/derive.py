"""From a motor description to every value of a motor profile, with the reason for each.

All arithmetic in SI units (speeds in rpm where named so). Phase quantities
are per phase; currents and voltages are peak amplitudes of the phase
sinusoid (the core's scales). The voltage limit is the one the core applies
(MC_VOLTAGE_LIMIT_FRACTION of the SVGen full scale Vbus/sqrt 3) less a
headroom for the current loops and the dead time.

Each derived value is stored as a Value(macro, number, unit, reason) so the
header writer can put the reason next to the number.
"""

from __future__ import annotations

import cmath
import math
from typing import Any

from . import cheader
from .units import RPM, SQRT3, TWO_PI, InputError

SPEED_PM_DEG = 40.0  # the speed loop's phase margin at the lightest claimed rotor
SPEED_ZERO_RATIO = 8.0  # the speed PI's zero at the crossover / this
SPEED_J_MIN_SCALE = 0.5  # the lightest rotor the profile claims, x the stated inertia (make robust draws 0.5..20)
START_LOAD_SHARE = 0.6  # the start load's share of the forced current's torque Kt I_ramp
# Lock current, in dead-time bands, the lock's dead-time measurement needs
# (mc_derived.h: 1.5 bands at 3/4 of the lock current times sqrt(3)/2).
DTM_LOCK_BANDS = 1.5 / (0.75 * SQRT3 / 2.0)
OL_DAMP_ZETA = 0.35  # open-loop damping ratio MOTOR_OL_DAMP_S is computed for (UserParms.h: why low)
# The fewest counts a PI gain may have in the core's Q15 form (mc_derived.h: a mantissa
# with a shift above 1): at 16 counts rounding alone moves it by up to 3 %; at 0 the loop
# does nothing. Fewer is a unit slip upstream (the shipped examples have 392 or more).
MIN_GAIN_COUNTS = 16
# The core's ranges of what this module derives (firmware/mc_derived.h, MC_CHECK):
KP_RANGE = 128.0  # MC_CUR_KP_, MC_SPD_KP_ < 128 (a Q15 mantissa shifted by at most 7)
KI_RANGE = 1.0  # MC_CUR_KI_, MC_SPD_KI_ < 1 (plain Q15, no shift)
LOCK_PERIODS_MAX = 65000.0  # MOTOR_LOCK_TIME_S x PWM_FREQUENCY_HZ <= 65000 (a uint16_t count)
OL_DAMP_PERIODS = (1.0 / 16.0, 1000.0)  # MOTOR_OL_DAMP_S x fpwm: one Q4 count .. 1000 periods
RAMP_STEP_INC_MIN = 8.0  # MC_RAMP_STEP_INC_: the 32-bit angle step grows by >= 8 a period
GAIN_MARGIN = 0.9  # a gain the tool lowers to fit a range stays this far inside it (rounding)


def gain_counts(x: float, integral: bool = False) -> int:
    """The integer the core stores for a gain of x full-scale units: Kp (MC_CUR_KP,
    MC_SPD_KP) as a Q15 mantissa with a shift, 0 <= x < 128; Ki (MC_CUR_KI, MC_SPD_KI)
    as plain Q15, 0 <= x < 1 (mc_derived.h). -1 outside the core's range."""
    if not 0.0 <= x < (KI_RANGE if integral else KP_RANGE):
        return -1
    return cheader.q15_round(x) if integral else cheader.mant_shift(x)[0]


class Infeasible(Exception):
    """The request cannot be met on this board: the message starts with the field."""

    def __init__(self, field, message):
        super().__init__(f"{field}: {message}")
        self.field = field


class Value:
    def __init__(self, macro: str, number: float, unit: str, reason: str, fmt: str = "{:.4g}") -> None:
        self.macro, self.number, self.unit, self.reason, self.fmt = macro, number, unit, reason, fmt


def fmt_num(x: float, fmt: str = "{:.4g}") -> str:
    s = fmt.format(x)
    if "e" not in s and "." not in s and "inf" not in s and "nan" not in s:
        s += ".0"
    return s


def sig(x, n=4):
    """x rounded to n significant digits (what the header prints)."""
    if x == 0:
        return 0.0
    return float(f"{x:.{n}g}")


def sig_down(x, n=3):
    """x rounded down to n significant digits (limits never round up)."""
    if x <= 0:
        return 0.0
    e = math.floor(math.log10(x)) - (n - 1)
    return float(f"{math.floor(x / 10.0**e + 1e-9)}e{e}")


def sig_up(x, n=3):
    """x rounded up to n significant digits: a value the core bounds from below (the lock
    current's dead-time bands) never rounds under its bound."""
    if x <= 0:
        return 0.0
    e = math.floor(math.log10(x)) - (n - 1)
    return float(f"{math.ceil(x / 10.0**e - 1e-9)}e{e}")


def round_up(x, step):
    return math.ceil(x / step - 1e-9) * step


def round_down(x, step):
    return math.floor(x / step + 1e-9) * step


class Tuning:
    """Every derived value; .values is the ordered list written to the header."""

    def __init__(self) -> None:
        self.values: list[Value] = []
        self.notes: list[str] = []  # the header's introduction
        self.warnings: list[str] = []  # derating: printed, and in the header
        self.limited: list[str] = []  # values held to the core's ranges: printed, and in the header
        self.fw_table: list[float] = []
        self.fw_speeds: list[float] = []
        self.by: dict[str, Value] = {}
        # the board and the motor as derive saw them (SI units; speeds rpm)
        self.desc: Any = None
        self.board = self.board_name = ""
        self.fpwm = 0
        self.i_fs = self.v_fs = self.vbus = self.psi = self.kt = self.v_ss = 0.0
        self.i_peak = self.i_qmax = self.trip = self.i_load = self.n_bus = self.id_limit = 0.0

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


def dead_time_band(t: Tuning, fcy: int, fpwm: int, vbus: float, l: float, i_fs: float, dt_ns: float) -> float:
    """The dead-time compensation's band (A): UserParms.h's default Vbus / (12 L fpwm), the
    phase current's ripple. The core (mc_derived.h MC_CHECK_FOR(MC_DEADTIME_BAND_A,
    MOTOR_LS_H)) wants it below I_FS / 4 and, in Q15 counts of current, above the dead
    time's counts (the in-band slope < 1): a large L (15 mH at 20 kHz on the MCLV) gets the
    narrowest band it allows, written into the profile (a wider band under-compensates a
    little; UserParms.h); an L so small that the ripple is a quarter of the scale is refused."""
    band = vbus / (12.0 * l * fpwm)
    if band >= 0.25 * i_fs:
        raise Infeasible("motor.inductance", f"the current ripple Vbus / (12 L fpwm) = {band:.3g} A is a quarter of "
                         f"the {i_fs:g} A current scale or more (MC_DEADTIME_BAND_A < I_FS / 4): L is too small "
                         f"for this board at {fpwm} Hz")
    counts = int(dt_ns * 1e-9 * fcy + 0.5)  # MC_DT_COUNTS
    band_min = sig_up((counts + 1.5) * i_fs / 32768.0, 3)  # Q15 counts of the band > MC_DT_COUNTS, rounding kept
    if band < band_min:
        band = t.held("MC_DEADTIME_BAND_A", band, band_min, math.inf,
                      f"above the {counts} dead-time counts in Q15 of the current scale (mc_derived.h "
                      f"MC_CHECK_FOR(MC_DEADTIME_BAND_A, MOTOR_LS_H): the in-band slope < 1)")
        t.add("MC_DEADTIME_BAND_A", band, "A",
              f"dead-time compensation band (UserParms.h): the ripple Vbus / (12 L fpwm) = "
              f"{vbus / (12.0 * l * fpwm):.3g} A is narrower than the core can represent against {counts} dead-time "
              f"counts: the narrowest it allows")
    return band


def bisect_last(pred, lo, hi, steps):
    """Narrows [lo, hi] with pred(lo) true and pred(hi) false for `steps` halvings;
    returns the last point known true."""
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        if pred(mid):
            lo = mid
        else:
            hi = mid
    return lo


def speed_margin(w, ws, zr, fc, loop_hz):
    """Phase margin (deg) of the speed loop crossing over at w (rad/s) when it was designed for
    ws: the PI zero at ws / zr; the speed filter as the core runs it, y += a (x - y) once a loop
    period T with a = 2 pi fc T; a delay of 1.5 T (the window's mean age, the hold of the Iq
    reference, the current loop)."""
    t = 1.0 / loop_hz
    a = TWO_PI * fc * t
    filt = a / (1.0 - (1.0 - a) * cmath.exp(-1j * w * t))
    return 90.0 - math.degrees(math.atan(ws / zr / w) - cmath.phase(filt) + 1.5 * w * t)


def speed_crossover(pm_deg, k, zr, fc, loop_hz):
    """The design crossover ws (rad/s) whose loop, crossing over at k x ws (a rotor of 1/k times
    the inertia), keeps pm_deg of phase margin there (the margin falls as w rises)."""
    return bisect_last(lambda ws: speed_margin(k * ws, ws, zr, fc, loop_hz) >= pm_deg, 1.0, 1e5, 60)


def id_for_voltage(w, r, l, psi, iq, vmax):
    """Smallest |Id| (Id <= 0) with |V| <= vmax in steady state at electrical speed w:
    Vd = R Id - w L Iq, Vq = R Iq + w (psi + L Id). None when no Id reaches it.
    |V|^2 - vmax^2 = A Id^2 + B Id + C, a quadratic in Id."""
    a_ = w * l * iq
    b_ = r * iq + w * psi
    A = r * r + (w * l) ** 2
    B = 2.0 * (b_ * w * l - r * a_)
    C = a_ * a_ + b_ * b_ - vmax * vmax
    if C <= 0.0:
        return 0.0
    disc = B * B - 4.0 * A * C
    if disc < 0.0:
        return None
    return min(0.0, (-B + math.sqrt(disc)) / (2.0 * A))


def derive(desc: Any) -> Tuning:
    t = Tuning()
    benv = cheader.board_env(desc.board)
    gb = benv.get
    i_fs = float(cheader.scale_value(benv, "BOARD_I_FULLSCALE_A", "the current scale"))
    vbus = float(cheader.scale_value(benv, "BOARD_VBUS_NOMINAL_V", "the bus voltage"))
    fcy = int(cheader.scale_value(benv, "BOARD_FCY_HZ", "the instruction clock", whole=True))
    td = benv.num("BOARD_DEADTIME_NS") * 1e-9
    board_name = str(gb("BOARD_NAME")) if benv.has("BOARD_NAME") else desc.board
    fpwm = int(round(desc.pwm_hz)) if desc.pwm_hz is not None else int(benv.num("PWM_FREQUENCY_HZ"))
    if not 4000 <= fpwm <= 40000 or fcy % fpwm != 0:
        raise InputError("pwm_frequency", f"{fpwm} Hz: must be 4..40 kHz and divide the {fcy} Hz instruction clock")
    # mc_derived.h MC_CHECK_FOR(BOARD_VBUS_FULLSCALE_V, PWM_FREQUENCY_HZ): the applied-voltage
    # scale MC_VAPP_K = sqrt 3 / (3 PWM_DUTY_MAX) x VBUS_FS / VBUS_NOMINAL x 2^25 in [1024, 32767)
    # (a faster PWM has fewer duty counts: the MCLV's 52.8 V scale over 24 V stops at 30.7 kHz)
    vapp = SQRT3 / 3.0 * benv.num("BOARD_VBUS_FULLSCALE_V") / vbus * 33554432.0  # x 1 / PWM_DUTY_MAX
    if not 1024.0 <= vapp / (fcy // fpwm) < 32767.0:
        raise InputError("pwm_frequency", f"{fpwm} Hz: the {board_name}'s applied-voltage scaling needs "
                         f"{fcy / (vapp / 1024.0):.0f}..{fcy / (vapp / 32767.0):.0f} Hz (mc_derived.h MC_VAPP_K)")
    loop_hz = int(cheader.scale_value(benv, "MC_SPEED_LOOP_HZ", "the speed-loop rate", whole=True))
    if fpwm % loop_hz != 0 or not 1 <= fpwm // loop_hz <= 256:
        raise InputError("pwm_frequency", f"{fpwm} Hz: must be 1..256 times the {loop_hz} Hz speed loop")
    vfrac = benv.num("MC_VOLTAGE_LIMIT_FRACTION")
    ts = 1.0 / fpwm
    pp, r, l = desc.pole_pairs, desc.r_ph, desc.l_ph
    v_fs = vbus / SQRT3
    t.board, t.fpwm, t.i_fs, t.v_fs, t.vbus, t.board_name = desc.board, fpwm, i_fs, v_fs, vbus, board_name
    t.desc = desc

    # ---- motor constants ----------------------------------------------------
    psi = desc.ke_ll / SQRT3 / (1000.0 * RPM * pp)  # V s/rad electrical (Wb)
    kt = 1.5 * pp * psi  # N m per A peak
    e_per_rpm = desc.ke_ll / SQRT3 / 1000.0  # phase peak volts per rpm
    t.psi, t.kt = psi, kt
    if ts * r / l >= 1.0:
        raise Infeasible("motor.inductance", f"Ts R / L = {ts * r / l:.3f} >= 1: L is too small for R at {fpwm} Hz "
                         "(the observer's F = 1 - Ts R/L would be <= 0); check the unit (mH?) and the PWM frequency")
    if ts / l * v_fs / i_fs >= 1.0:
        raise Infeasible("motor.inductance", f"G = Ts/L * V_FS/I_FS = {ts / l * v_fs / i_fs:.2f} >= 1: L too small for "
                         f"the {board_name} scales ({v_fs:.1f} V, {i_fs:g} A)")

    # ---- voltage available in steady state -----------------------------------
    # The shunt window keeps the measured phases' duties at or below
    # MC_DUTY_SAMPLE_MAX (mc_derived.h), so no line-to-line duty difference
    # involving them exceeds it: a circle wider than that fraction is not
    # available in every sector.
    dt_frac = td * fpwm
    headroom = 1.0 - 0.05 - dt_frac
    win = cheader.duty_sample_max(fcy, fpwm, benv.num("PWM_ADC_TRIGGER_TCY"), benv.num("PWM_DEADTIME_NS"),
                                  benv.num("BOARD_SHUNT_MIN_ON_NS")) / (fcy // fpwm)
    vfrac_ss = min(vfrac, win)
    v_ss = vfrac_ss * v_fs * headroom
    t.v_ss = v_ss
    if vfrac_ss < vfrac:
        limit = (f"{vfrac_ss:.3f} (the shunt window: the measured phases' duties stay at or below "
                 f"{100 * win:.1f} %, MC_DUTY_SAMPLE_MAX; MC_VOLTAGE_LIMIT_FRACTION is {vfrac:g})")
    else:
        limit = f"{vfrac:g} (MC_VOLTAGE_LIMIT_FRACTION)"
    t.notes.append(
        f"Steady-state voltage budget: {limit} x {vbus:g} V / sqrt 3 = {vfrac_ss * v_fs:.2f} V phase peak, "
        f"times {headroom:.2f} (5 % left to the current loops, {100 * dt_frac:.0f} % = dead time "
        f"{td * 1e6:g} us x {fpwm} Hz) = {v_ss:.2f} V.")

    # ---- currents and the board ---------------------------------------------
    trip_board = 0.9 * i_fs
    i_peak_req = desc.i_peak if desc.i_peak is not None else desc.i_rated
    trip = min(trip_board, 1.25 * i_peak_req)
    i_total = 0.9 * trip  # what mc.c lets |(Id, Iq)| reach (MC_I_TOTAL)
    derated = i_total < i_peak_req - 1e-9
    i_peak = min(i_peak_req, i_total)
    i_qmax = min(desc.i_rated, i_peak)
    t.i_peak, t.i_qmax, t.trip = i_peak, i_qmax, trip
    if derated:
        msg = (f"derated: the {board_name} reads +-{i_fs:g} A, the trip must stay below 90 % of it "
               f"({trip_board:.2f} A) and the core holds |I| to 90 % of the trip, so the motor's "
               f"{i_peak_req:.3g} A peak is limited to {i_peak:.3g} A ({100 * i_peak / i_peak_req:.0f} % of its torque)")
        t.warnings.append(msg)
    t.add("MOTOR_OVERCURRENT_A", sig(trip, 3), "A",
          f"software trip: min(90 % of the {i_fs:g} A current full scale = {trip_board:.3g} A, so one sample "
          f"of overshoot still reads inside the ADC range; 1.25 x the peak current {i_peak_req:.3g} A)")
    t.add("MOTOR_CURRENT_MAX_A", sig_down(i_qmax, 3), "A",
          f"|Iq| limit of the speed loop: the rated {desc.i_rated:.3g} A peak" +
          (f", {msg}" if derated else " (continuous torque)"))
    i_qmax = t["MOTOR_CURRENT_MAX_A"]

    # ---- speeds -------------------------------------------------------------
    # Load current the voltage budget is computed for: the field-weakening
    # table and the nominal speed are exact at this Iq (more load at the same
    # speed asks for more voltage; the current loops' 5 % headroom covers some).
    i_load = desc.i_fw_load if desc.i_fw_load is not None else 0.25 * i_qmax
    if i_load > i_qmax:
        raise Infeasible("application.fw_load_current", f"{i_load:.3g} A exceeds the Iq limit {i_qmax:.3g} A")
    t.i_load = i_load

    def v_at(n, i_d, i_q):
        w = n * RPM * pp
        return math.hypot(r * i_d - w * l * i_q, r * i_q + w * (psi + l * i_d))

    # Nominal speed: highest speed with Id = 0 inside the budget (bisection).
    def inside_at_id0(n):
        return v_at(n, 0.0, i_load) < v_ss

    hi = 1.0
    while inside_at_id0(hi) and hi < 1e7:
        hi *= 2.0
    n_bus = bisect_last(inside_at_id0, 0.0, hi, 80)
    t.n_bus = n_bus
    n_top = desc.n_max if desc.n_max is not None else desc.n_rated
    top_field = "application.max_speed" if desc.n_max is not None else "motor.rated_speed"
    # Id limit: the total current may reach i_peak (|(Id, Iq_load)| <= i_peak).
    id_limit = -math.sqrt(max(i_peak * i_peak - i_load * i_load, 0.0))
    id_limit = max(id_limit, -0.95 * i_fs)

    def id_needed(n):
        return id_for_voltage(n * RPM * pp, r, l, psi, i_load, v_ss)

    if n_top <= n_bus:
        n_nom = round_down(n_top, 10.0)
        n_fw = n_nom
        fw_reason = (f"= the top speed {n_top:.0f} rpm ({top_field}): the bus reaches {n_bus:.0f} rpm without "
                     f"field weakening at Iq = {i_load:.2g} A, so none is needed (AN1078: nominal = FW max disables it)")
    else:
        # Highest speed reachable with Id inside the current limit.
        def reachable(n):
            i_d = id_needed(n)
            return i_d is not None and i_d >= id_limit

        if not reachable(n_top):
            lo = bisect_last(reachable, n_bus, n_top, 60)
            raise Infeasible(
                top_field,
                f"{n_top:.0f} rpm is beyond the {vbus:g} V bus even with field weakening: at most "
                f"{round_down(lo, 10):.0f} rpm with |I| <= {i_peak:.3g} A (Id >= {id_limit:.2f} A at Iq = "
                f"{i_load:.2g} A; raise motor.peak_current or lower the speed)")
        n_nom = round_down(n_bus, 10.0)
        n_fw = n_top
        fw_reason = (f"highest speed with Id = 0: back-EMF {e_per_rpm * 1000:.3f} V/krpm phase peak plus the R and "
                     f"wL drops at Iq = {i_load:.2g} A reach the {v_ss:.2f} V budget at {n_bus:.0f} rpm")
    t.add("MOTOR_SPEED_NOMINAL_RPM", n_nom, "rpm", fw_reason, "{:.1f}")
    t.add("MOTOR_SPEED_FW_MAX_RPM", n_fw, "rpm",
          f"top speed asked for ({top_field})" + ("" if n_fw > n_nom else ", no field weakening"), "{:.1f}")

    # Field-weakening table: 16 points from nominal to FW max.
    tab, speeds = [], []
    for k in range(16):
        n = n_nom + (n_fw - n_nom) * k / 15.0
        i_d = 0.0 if (k == 0 or n_fw <= n_nom) else id_needed(n)
        if i_d is None or i_d < id_limit - 1e-9:
            raise Infeasible(top_field, f"field weakening fails at {n:.0f} rpm")  # guarded above
        tab.append(round(i_d, 3) + 0.0)
        speeds.append(n)
    for k in range(1, 16):  # rounding must not break monotony
        tab[k] = min(tab[k], tab[k - 1])
    t.fw_table, t.fw_speeds, t.id_limit = tab, speeds, id_limit

    # Speed full scale: 1.5 x the top speed, a round 1000 rpm, inside the core's ranges.
    fs = round_up(1.5 * n_fw, 1000.0)
    fs_max = min(fpwm * 60.0 / (TWO_PI * pp) * 0.95,  # smc: 2 pi omega_fs Ts < 1
                 fpwm * 60.0 / (3.0 * pp) * 0.95,  # mc.c: 3 omega_fs Ts < 1
                 32767.0 * benv.num("MC_SPEED_RAMP_RPM_PER_S") / loop_hz)  # slew >= 1 count
    # The stall detector's speed error is a fixed number of rpm (UserParms.h, 1500) the core
    # wants inside the speed scale (mc_derived.h MC_CHECK_FOR(MC_STALL_SPEED_ERROR_RPM,
    # MC_SPEED_FULLSCALE_RPM)): a slow motor (top speed under 1000 rpm) gets a wider scale.
    stall_err = benv.num("MC_STALL_SPEED_ERROR_RPM")
    fs = t.held("MOTOR_SPEED_FULLSCALE_RPM", fs, round_up(stall_err + 1.0, 1000.0), math.inf,
                f"above MC_STALL_SPEED_ERROR_RPM = {stall_err:g} rpm (mc_derived.h "
                f"MC_CHECK_FOR(MC_STALL_SPEED_ERROR_RPM, MC_SPEED_FULLSCALE_RPM))")
    fs = min(fs, round_down(fs_max, 100.0))
    if fs < n_fw / 0.95:
        raise Infeasible(top_field, f"{n_fw:.0f} rpm x {pp} pole pairs is too fast for {fpwm} Hz PWM "
                         f"(speed full scale would have to exceed {fs_max:.0f} rpm); raise pwm_frequency")
    if fs <= stall_err:
        raise Infeasible("pwm_frequency", f"{fpwm} Hz with {pp} pole pairs limits the speed scale to {fs_max:.0f} rpm, "
                         f"not above the stall detector's {stall_err:g} rpm (MC_STALL_SPEED_ERROR_RPM)")
    t.add("MOTOR_SPEED_FULLSCALE_RPM", fs, "rpm",
          "Q15 full scale of every speed: 1.5 x the top speed rounded up to 1000 rpm (room for overshoot, "
          "core check FW max <= 0.95 x full scale)", "{:.1f}")

    # Lowest closed-loop speed: the estimator needs a back-EMF well above the
    # voltage error of the dead time (square wave, fundamental 4/pi x 2/3 x
    # Td fpwm Vbus), which the core compensates only approximately.
    v_dt = 4.0 / math.pi * 2.0 / 3.0 * dt_frac * vbus
    n_emf = 3.0 * v_dt / e_per_rpm
    n_min = desc.n_min if desc.n_min is not None else round_up(max(n_emf, 0.08 * n_fw), 50.0)
    if n_min >= n_nom:
        raise Infeasible("application.min_speed" if desc.n_min is not None else top_field,
                         f"lowest closed-loop speed {n_min:.0f} rpm is not below the nominal {n_nom:.0f} rpm")
    t.add("MOTOR_SPEED_MIN_RPM", n_min, "rpm",
          ("given (application.min_speed)" if desc.n_min is not None else
           f"max(back-EMF = 3 x the dead-time voltage error {v_dt:.2f} V -> {n_emf:.0f} rpm, 8 % of the top "
           f"speed), rounded up to 50 rpm; the estimator's filter floor (MC_ESTIMATOR_MIN_RPM) is 0.8 x the "
           f"ramp end"), "{:.1f}")

    # ---- start-up -----------------------------------------------------------
    # The start-up current: the load must take at most START_LOAD_SHARE of the
    # forced current's torque Kt I, so the rotor runs at a load angle of at
    # most 37 deg behind the forced angle (the ramp's acceleration takes 20 %
    # more, below) and a plant with 15 % less back-EMF constant still starts.
    i_default = sig(min(0.6 * desc.i_rated, 0.6 * i_qmax), 3)
    if desc.t_start is not None:
        i_need = desc.t_start / (START_LOAD_SHARE * kt)
        if i_need > i_qmax:
            raise Infeasible("application.start_load",
                             f"{desc.t_start:g} N m needs {i_need:.3g} A of start-up current (the load at most "
                             f"{START_LOAD_SHARE:.0%} of Kt I, Kt = {kt * 1000:.2f} mN m/A), above the Iq limit "
                             f"{i_qmax:.3g} A: the motor cannot start this load")
        # rounded up, less 0.05 %: the 60 % share is the tool's margin, not a limit of the core
        i_lock = max(i_default, sig_up(i_need / 1.0005, 3))
        lock_reason = (f"the start load {desc.t_start * 1000:.3g} mN m at {START_LOAD_SHARE:.0%} of Kt I "
                       f"(Kt = {kt * 1000:.2f} mN m/A) -> {i_need:.3g} A, at least 0.6 x the continuous current "
                       f"{min(desc.i_rated, i_qmax):.3g} A: the lock pulls the rotor against the same load")
        t_start = desc.t_start
    else:
        i_lock = i_default
        lock_reason = (f"0.6 x the continuous current {min(desc.i_rated, i_qmax):.3g} A: pulls the rotor to the lock "
                       f"angle against cogging and friction (AN1078 INITIALTORQUE 1.0 A for the 1.64 A Hurst); no "
                       f"start load given, so the start is sized for {START_LOAD_SHARE:.0%} of Kt x that")
        t_start = START_LOAD_SHARE * kt * i_lock
    # The firmware measures the inverter's dead time at the lock (mc.c note 4,
    # MC_DEADTIME_MEASURE): 3/4 of the lock current must put 1.5 dead-time
    # bands (MC_DEADTIME_BAND_A) into phases B and C, I_lock >= 2.31 bands;
    # mc_derived.h refuses less.
    band_dt = dead_time_band(t, fcy, fpwm, vbus, l, i_fs, benv.num("PWM_DEADTIME_NS"))
    i_dtm = DTM_LOCK_BANDS * band_dt
    if i_lock < i_dtm:
        if i_dtm > i_qmax:
            raise Infeasible("motor.inductance",
                             f"measuring the dead time at the lock needs {i_dtm:.3g} A of lock current "
                             f"({DTM_LOCK_BANDS:.2f} x the dead-time band {band_dt:.3g} A), above the Iq limit "
                             f"{i_qmax:.3g} A: L is too small for this bus (or build with MC_DEADTIME_MEASURE 0)")
        i_lock = sig_up(i_dtm, 3)
        lock_reason += (f"; raised to {i_lock:.3g} A, {DTM_LOCK_BANDS:.2f} dead-time bands (MC_DEADTIME_BAND_A = "
                        f"{band_dt:.3g} A), the least the lock's dead-time measurement needs")
    t.add("MOTOR_LOCK_CURRENT_A", i_lock, "A", lock_reason)
    j = desc.j
    if j is not None:
        wn = math.sqrt(pp * kt * i_lock / j)  # rotor swing in the lock torque spring, rad/s
        t_lock = min(max(round_up(8.0 * TWO_PI / wn, 0.01), 0.1), 2.0)
        # the core counts the lock in a uint16_t of periods (2 s is 80000 at 40 kHz)
        t_lock = t.held("MOTOR_LOCK_TIME_S", t_lock, 0.0, round_down(LOCK_PERIODS_MAX / fpwm, 0.01),
                        f"at most {LOCK_PERIODS_MAX:.0f} PWM periods (mc_derived.h MC_CHECK(MOTOR_LOCK_TIME_S))")
        t.add("MOTOR_LOCK_TIME_S", t_lock, "s",
              f"8 periods of the rotor's small swing about the lock angle, w = sqrt(p Kt I_lock / J) = {wn:.0f} "
              f"rad/s (Kt = {kt * 1000:.2f} mN m/A, J = {j:.3g} kg m^2), within 0.1..2 s: a rotor that starts "
              f"near the unstable point 180 deg away takes several small-swing periods to fall in (4 periods "
              f"failed a start from 160 deg in the simulator)")
    else:
        t.add("MOTOR_LOCK_TIME_S", 0.25, "s", "no inertia given: AN1078's LOCKTIMEINSEC")
    i_ramp = min(i_lock, i_qmax)
    n_end = n_min
    if j is not None:
        alpha = 0.2 * kt * i_ramp / j  # rad/s^2: 20 % of the ramp torque accelerates J
        t_ramp_acc = n_end * RPM / alpha
        t_ramp = min(max(round_up(t_ramp_acc, 0.05), 1.0), 10.0)
        ramp_reason = (f"constant acceleration {alpha / RPM:.0f} rpm/s up to the ramp end: 20 % of the ramp torque "
                       f"Kt x {i_ramp:.3g} A = {kt * i_ramp * 1000:.1f} mN m accelerates J (the rest is margin for load "
                       f"and the lag of the forced angle) -> {t_ramp_acc:.3f} s; at least 1 s, so the rotor's swing from the "
                       f"lock dies into the ramp and the observer converges before the hand-off (0.5 s lost 1 to 2 "
                       f"of the simulator's 100 random-angle starts under load)")
    else:
        t_ramp = 1.0
        ramp_reason = "no inertia given: 1 s to the ramp end (AN1078 used 5 s with a brake attached)"
    # The forced angle's 32-bit step grows by MC_RAMP_STEP_INC_ = end step / ramp periods each
    # period, at least 8 counts: a low ramp end (1 pole pair, 40 kHz) needs a shorter ramp.
    t_ramp_max = round_down(n_end * pp / 60.0 * 4294967296.0 / (RAMP_STEP_INC_MIN * fpwm * fpwm), 0.05)
    if t_ramp_max < 100.0 / fpwm:  # and at least 100 periods; 9 rpm x pole pairs at 40 kHz still fits
        raise Infeasible("application.min_speed" if desc.n_min is not None else top_field,
                         f"the open-loop ramp to {n_end:.0f} rpm cannot be 100 PWM periods long with the forced "
                         f"angle's step growing >= {RAMP_STEP_INC_MIN:.0f} counts a period (mc_derived.h "
                         f"MC_CHECK(MOTOR_RAMP_TIME_S))")
    t_ramp = t.held("MOTOR_RAMP_TIME_S", t_ramp, 0.0, t_ramp_max,
                    f"the forced angle's step must grow by >= {RAMP_STEP_INC_MIN:.0f} counts a period "
                    f"(mc_derived.h MC_CHECK(MOTOR_RAMP_TIME_S))")
    t.add("MOTOR_RAMP_TIME_S", t_ramp, "s", ramp_reason)
    t.add("MOTOR_RAMP_END_RPM", n_end, "rpm", "hand-off to closed loop at the lowest closed-loop speed", "{:.1f}")
    t.add("MOTOR_RAMP_CURRENT_A", i_ramp, "A", "Iq during the open-loop ramp: the lock current")
    t.add("MOTOR_START_LOAD_NM", sig(t_start, 4), "N m",
          "the load torque the start-up is sized for (data for tools: the robustness campaign draws loads up to it)")
    if j is not None:
        wn_ol = math.sqrt(pp * kt * i_ramp / j)
        lo, hi = OL_DAMP_PERIODS
        damp = t.held("MOTOR_OL_DAMP_S", sig(2.0 * OL_DAMP_ZETA / wn_ol, 3), sig_up(lo / fpwm, 3),
                      sig_down(hi / fpwm, 3), f"{lo:g}..{hi:g} PWM periods (mc_derived.h MC_CHECK(MOTOR_OL_DAMP_S))")
        t.add("MOTOR_OL_DAMP_S", damp, "s",
              f"open-loop damping (UserParms.h): zeta {OL_DAMP_ZETA} for the rotor's swing about the forced angle, "
              f"w = sqrt(p Kt I_ramp / J) = {wn_ol:.0f} rad/s: 2 zeta / w")

    # ---- observer ------------------------------------------------------------
    e_top = e_per_rpm * n_fw
    e_seen = min(e_top, vfrac * v_fs)
    ks = sig(min(1.5 * e_seen, 0.97 * v_fs), 4)
    t.add("MOTOR_SMC_GAIN_V", ks, "V",
          f"Kslide = min(1.5 x the largest back-EMF the observer sees, 97 % of V_FS = {0.97 * v_fs:.3g} V, the "
          f"cap of the hand-tuned profiles; the core allows 2 V_FS, docs/estimator.md wants Kslide above that "
          f"back-EMF); "
          f"that back-EMF is min(Ke at the top speed = {e_top:.3g} V, the voltage limit {vfrac * v_fs:.3g} V: "
          f"above nominal field weakening holds it there)")
    spd_fc = loop_hz / 10.0
    t.add("MC_SPEED_FILTER_HZ", spd_fc, "Hz",
          f"estimated-speed filter cut-off: a tenth of the {loop_hz} Hz speed-loop rate (docs/estimator.md: 100 Hz "
          f"at a 1 kHz window converges fastest from a wrong state; the core needs 2 pi fc / loop rate < 1)",
          "{:.1f}")
    f_ex = math.exp(-ts * r / l)
    g_si = (1.0 - f_ex) / r  # A per V per period
    band = sig(ks * g_si / f_ex, 3)
    # The core wants the band below the current scale (mc_derived.h
    # MC_CHECK_FOR(MOTOR_SMC_LINEAR_BAND_A, BOARD_I_FULLSCALE_A)); a small L at a large Ts R/L
    # asks for more. A narrower band only raises the linear band's loop gain c = G Kslide / band
    # above F (smc.h note 3: still linear below 1 + F, relay mode above, which the core allows).
    band_max = sig_down(0.99 * i_fs, 3)
    if band > band_max:
        c = ks * g_si / band_max
        mode = f"linear, c < 1 + F = {1.0 + f_ex:.3f}" if c < 1.0 + f_ex else "relay mode, c >= 1 + F (smc.h note 4)"
        band = t.held("MOTOR_SMC_LINEAR_BAND_A", band, 0.0, band_max,
                      f"below the {i_fs:g} A current scale (mc_derived.h MC_CHECK_FOR(MOTOR_SMC_LINEAR_BAND_A)); "
                      f"the band's loop gain c = {c:.3f} instead of the dead-beat F = {f_ex:.3f} ({mode})")
    t.add("MOTOR_SMC_LINEAR_BAND_A", band, "A",
          f"MaxSMCError = Kslide G / F (smc.h SMC_MAXERR_DEADBEAT: the linear band's loop gain G Kslide/MaxSMCError "
          f"equals F, a dead-beat correction), G = (1 - F)/R = {g_si:.5f} A/V, F = {f_ex:.5f}")
    if band <= i_fs / 32768.0 * 4:
        raise Infeasible("motor.inductance", "the observer's linear band is below 4 LSB of the current scale")

    # ---- current PI ----------------------------------------------------------
    pm = 70.0
    wc_max = math.radians(90.0 - pm) / (1.5 * ts)
    if desc.wc is not None:
        wc = desc.wc
        wc_reason = f"given (application.current_bandwidth); the delay-limited maximum is {wc_max:.0f} rad/s"
        if wc > wc_max * 1.5:
            raise Infeasible("application.current_bandwidth",
                             f"{wc:.0f} rad/s is beyond what {fpwm} Hz sampling allows (1.5 Ts delay: "
                             f"{wc_max:.0f} rad/s for a {pm:.0f} deg phase margin)")
    else:
        # Noise: one ADC count of current (10-bit ADC over +-I_FS, dsPIC33F ADC1) times Kp is
        # voltage noise the observer sees as back-EMF; keep it within 2 % of the back-EMF at
        # the lowest closed-loop speed.
        adc_bits = int(benv.num("BOARD_ADC_BITS")) if benv.has("BOARD_ADC_BITS") else 10
        i_count = 2.0 * i_fs / (1 << adc_bits)
        wc_noise = 0.02 * e_per_rpm * n_min / i_count / l
        wc = round_down(min(wc_max, wc_noise), 100.0)
        wc_reason = (f"min(delay: {pm:.0f} deg phase margin with the 1.5 Ts loop delay, (90 - {pm:.0f}) deg / "
                     f"(1.5 Ts) = {wc_max:.0f} rad/s; noise: Kp x one ADC count ({i_count * 1e3:.2f} mA) within "
                     f"2 % of the back-EMF at the lowest closed-loop speed ({e_per_rpm * n_min:.2f} V), "
                     f"{wc_noise:.0f} rad/s), rounded down to 100 rad/s (in the simulator the delay limit "
                     f"alone, 4600 rad/s, lost the Hurst's 500 rpm operation)")
        # The gains' Q15 ranges (Ki = R wc Ts I_FS / V_FS < 1: a high-resistance motor on a
        # board with a large current scale): the bandwidth is lowered, the zero still cancels.
        wc_q = GAIN_MARGIN * min(KI_RANGE * v_fs / (i_fs * r * ts), KP_RANGE * v_fs / (i_fs * l))
        if wc_q < wc:
            wc = t.held("MOTOR_CURRENT_LOOP_BW_RAD_S", wc, 0.0, round_down(wc_q, 100.0),
                        "the current PI's Q15 ranges, Ki Ts I_FS / V_FS < 1 and Kp I_FS / V_FS < 128 "
                        "(mc_derived.h MC_CHECK(MOTOR_CURRENT_KI_V_PER_AS))")
            wc_reason += f"; lowered to {wc:.0f} rad/s so the gains fit the core's Q15 ranges"
    t.add("MOTOR_CURRENT_LOOP_BW_RAD_S", wc, "rad/s",
          f"current-loop bandwidth, {wc / TWO_PI:.0f} Hz: {wc_reason}", "{:.1f}")
    t.add("MOTOR_CURRENT_KP_V_PER_A", sig(l * wc, 4), "V/A",
          f"Kp = L wc = {l * 1e3:.4g} mH x wc: pole-zero cancellation (the PI zero Ki/Kp = R/L cancels the "
          f"winding pole, tau = {l / r * 1e3:.3g} ms), leaving a first-order loop of bandwidth wc")
    t.add("MOTOR_CURRENT_KI_V_PER_AS", sig(r * wc, 4), "V/(A s)", f"Ki = R wc = {r:.4g} ohm x wc", "{:.6g}")
    for macro, x, fld, integral in (
            ("MOTOR_CURRENT_KP_V_PER_A", t["MOTOR_CURRENT_KP_V_PER_A"] * i_fs / v_fs, "motor.inductance", False),
            ("MOTOR_CURRENT_KI_V_PER_AS", t["MOTOR_CURRENT_KI_V_PER_AS"] * ts * i_fs / v_fs, "motor.resistance", True)):
        fld = "application.current_bandwidth" if desc.wc is not None else fld
        _gain_fits(t, macro, x, integral, fld, "the current loop could not act; check the value and its unit")

    # ---- speed PI ------------------------------------------------------------
    # Gain schedule of the core (mc.c): Kp is full above MOTOR_SPEED_KP_FULL_RPM and scaled
    # by |speed ref| / that below it (never under MC_SPEED_KP_MIN_FRACTION).
    n_kp_full = min(round_up(3.0 * n_min, 100.0), n_fw)
    t.add("MOTOR_SPEED_KP_FULL_RPM", n_kp_full, "rpm",
          "speed-PI Kp is full above this speed and reduced below it (the core's gain schedule): 3 x the lowest "
          "closed-loop speed, where the back-EMF is 3 x its smallest usable value and the estimated speed is "
          "clean enough for the full gain (the hand-tuned profiles use the same ratio)", "{:.1f}")
    kp_si_to_rpm = RPM  # A per (rad/s) -> A per rpm
    if j is not None:
        # The crossover is chosen for the lightest rotor the profile claims (SPEED_J_MIN_SCALE of
        # the stated J: the real crossover scales as 1/J): there the phase margin, counting the
        # PI zero (ws/8), the speed filter (the core's one-pole filter run at the loop rate) and
        # the loop's 1.5-period delay, is SPEED_PM_DEG. The sampled-loop rule, loop rate / 20, caps it.
        zr = SPEED_ZERO_RATIO
        ws_pm = speed_crossover(SPEED_PM_DEG, 1.0 / SPEED_J_MIN_SCALE, zr, spd_fc, loop_hz)
        ws_cap = TWO_PI * loop_hz / 20.0
        ws = min(ws_pm, ws_cap, wc / 8.0)
        # the core's Q15 ranges: Ki / loop * FS / I_FS < 1 and Kp * FS / I_FS < 128 (keep 10 % margin)
        kp_per_ws = j / kt * kp_si_to_rpm  # A/rpm per rad/s of crossover
        ws_q = min(math.sqrt(0.9 * zr * loop_hz * i_fs / fs / kp_per_ws), 100.0 * i_fs / fs / kp_per_ws)
        ws_reason = (f"{SPEED_PM_DEG:.0f} deg of phase margin at {1.0 / SPEED_J_MIN_SCALE:g} x this crossover, "
                     f"where a rotor of {SPEED_J_MIN_SCALE:g} x the stated J puts it")
        if ws_cap < ws_pm:
            ws_reason = f"2 pi x {loop_hz} Hz / 20 = {ws_cap:.0f} rad/s (the sampled-loop cap)"
        if ws_q < ws:
            ws = ws_q
            ws_reason += f", lowered to {ws:.0f} rad/s so Ki fits the core's Q15 range (large J)"
        if wc / 8.0 < min(ws_pm, ws_cap):
            ws_reason += f", capped at wc/8 = {wc / 8.0:.0f} rad/s (cascade: the current loop 8 x faster)"
        pm_nom = speed_margin(ws, ws, zr, spd_fc, loop_hz)
        kp = j * ws / kt
        ki = kp * ws / zr
        t.add("MOTOR_SPEED_KP_A_PER_RPM", sig(kp * kp_si_to_rpm, 3), "A/rpm",
              f"Kp = J ws / Kt with the speed-loop crossover ws = {ws:.0f} rad/s, J = {j:.3g} kg m^2, Kt = 1.5 p psi "
              f"= {kt * 1000:.2f} mN m/A. ws = {ws_reason}; the margin counts the PI zero, the {spd_fc:g} Hz "
              f"speed filter and the 1.5-period delay ({pm_nom:.0f} deg at the stated J; docs/tune.md). A "
              f"larger real J lowers the crossover; a smaller one raises it.")
        t.add("MOTOR_SPEED_KI_A_PER_RPM_S", sig(ki * kp_si_to_rpm, 3), "A/(rpm s)",
              f"Ki = Kp ws / {zr:g}: the PI zero {zr:g} x below the crossover, integral action quick enough to "
              f"recover a half-rated load step within 100 ms, slow enough to keep the margin at 20 x the stated J "
              f"(docs/tune.md)")
    else:
        kp_rpm = i_qmax / (0.4 * n_fw)
        t.add("MOTOR_SPEED_KP_A_PER_RPM", sig(kp_rpm, 3), "A/rpm",
              "no inertia given (safe default): a speed error of 40 % of the top speed asks for the full Iq limit")
        t.add("MOTOR_SPEED_KI_A_PER_RPM_S", sig(kp_rpm * 5.0, 3), "A/(rpm s)",
              "no inertia given (safe default): integral time Kp/Ki = 0.2 s, slow enough for a heavy load")

    # Both speed gains as the core stores them: counts that round to (nearly) 0 are an inertia
    # in the wrong unit (g cm^2 read as kg m^2 gives gains 1e7 times too small).
    fld = "motor.inertia" if j is not None else "motor.rated_current"
    hint = ("the speed loop could not act; did you mean kg cm^2 or g cm^2 for a value written in kg m^2, or "
            "the reverse?" if j is not None else "the speed loop could not act; check the value and its unit")
    for macro, x, integral in (("MOTOR_SPEED_KP_A_PER_RPM", t["MOTOR_SPEED_KP_A_PER_RPM"] * fs / i_fs, False),
                               ("MOTOR_SPEED_KI_A_PER_RPM_S", t["MOTOR_SPEED_KI_A_PER_RPM_S"] / loop_hz * fs / i_fs,
                                True)):
        _gain_fits(t, macro, x, integral, fld, hint)
    return t


def _gain_fits(t: Tuning, macro: str, x: float, integral: bool, fld: str, hint: str) -> None:
    """A gain of x full-scale units as the core stores it (gain_counts): beyond the core's
    range the board cannot take it (Infeasible); too few counts is a unit slip (InputError);
    both name the description's field."""
    n = gain_counts(x, integral)
    if n < 0:
        hi = KI_RANGE if integral else KP_RANGE
        raise Infeasible(fld, f"gives {macro} = {t[macro]:g}, {x:.3g} in the core's units, outside its Q15 range "
                         f"[0, {hi:g}) (mc_derived.h MC_CHECK({macro}))")
    if n < MIN_GAIN_COUNTS:
        raise InputError(fld, f"gives {macro} = {t[macro]:g}, {n} counts in the core's Q15 form (at least "
                         f"{MIN_GAIN_COUNTS}): {hint}")
