"""Read the firmware's C profiles and compute what the core derives from them.

`read_defines` collects the object-like #define values of a list of headers
the way the preprocessor sees them through their #ifndef guards (the first
definition wins: the motor profile, then the board, then UserParms.h's
defaults), plus the X-macro field-weakening table. `derive_core` replays the
arithmetic of firmware/mc_derived.h, smc_estimator/smc.h (SMC_PARAMS_INIT)
and the checks of firmware/mc.c in double precision, giving every Q15 integer
the core will compile in and every range check it will apply.
"""

import math
import os
import re

from .units import InputError

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
FIRMWARE = os.path.join(REPO, "firmware")
SQRT3 = 1.7320508075688772
TWO_PI = 6.283185307179586

_CAST_RE = re.compile(
    r"\(\s*(?:double|float|long|int|unsigned|uint8_t|int8_t|uint16_t|int16_t|uint32_t|int32_t|q15_t)\s*\)"
)
_SUFFIX_RE = re.compile(r"\b(\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)(?:UL|LU|L|U|ul|l|u)\b")
_IDENT_RE = re.compile(r"\b[A-Za-z_]\w*\b")


def _logical_lines(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    text = text.replace("\\\n", " ")
    return text.split("\n")


def read_defines(paths):
    """{name: raw text} of object-like macros and {name: [args]} of X-macros."""
    raw, xtables = {}, {}
    for path in paths:
        with open(path, encoding="utf-8") as f:
            lines = _logical_lines(f.read())
        for line in lines:
            m = re.match(r"\s*#\s*define\s+(\w+)\(X\)\s+(.*)$", line)
            if m:
                if m.group(1) not in xtables:
                    xtables[m.group(1)] = [a.strip() for a in re.findall(r"X\(([^()]*)\)", m.group(2))]
                continue
            m = re.match(r"\s*#\s*define\s+(\w+)(?:\s+(.*))?$", line)
            if m and "(" not in m.group(1):
                name, body = m.group(1), (m.group(2) or "").strip()
                if name not in raw:
                    raw[name] = body
    return raw, xtables


class Env:
    """Evaluates macro values as numbers (or strings) on demand."""

    def __init__(self, raw, xtables):
        self.raw, self.xtables, self.cache = raw, xtables, {}

    def has(self, name):
        return name in self.raw

    def get(self, name, _depth=0):
        if name in self.cache:
            return self.cache[name]
        if name not in self.raw:
            raise KeyError(name)
        if _depth > 50:
            raise ValueError(f"{name}: recursive definition")
        body = self.raw[name]
        if body.startswith('"'):
            val = body.strip('"')
        else:
            val = self.eval(body, _depth)
        self.cache[name] = val
        return val

    def eval(self, expr, _depth=0):
        e = _CAST_RE.sub("", expr)
        e = _SUFFIX_RE.sub(r"\1", e)
        e = e.replace("&&", " and ").replace("||", " or ")
        names = {}
        for ident in set(_IDENT_RE.findall(e)):
            if ident in ("and", "or", "not") or re.fullmatch(r"[eE]\d*", ident):
                continue
            names[ident] = self.get(ident, _depth + 1)
        return eval(e, {"__builtins__": {}}, names)  # noqa: S307 - our own headers

    def table(self, name):
        return [float(self.eval(a)) for a in self.xtables[name]]


def _board_header(board):
    """firmware/boards/board_<board>.h, or InputError naming the boards there are."""
    board_h = os.path.join(FIRMWARE, "boards", f"board_{board}.h")
    if not os.path.exists(board_h):
        have = sorted(f[6:-2] for f in os.listdir(os.path.join(FIRMWARE, "boards")) if f.startswith("board_"))
        raise InputError("board", f"no firmware/boards/board_{board}.h (boards: {', '.join(have)})")
    return board_h


def profile_env(motor_header, board):
    """Env of a motor header as built with BOARD=board (first definition wins:
    motor, board, UserParms.h)."""
    board_h = _board_header(board)
    # UserParms.h includes the board first, then the motor; both are #ifndef
    # guarded per macro, and no macro is defined in both, so either order
    # gives the same values; the motor's overrides of UserParms defaults
    # (PWM_FREQUENCY_HZ...) must come before UserParms.h.
    raw, xt = read_defines([board_h, motor_header, os.path.join(FIRMWARE, "UserParms.h")])
    return Env(raw, xt)


def board_env(board):
    """Env of a board with UserParms.h's defaults (no motor)."""
    raw, xt = read_defines([_board_header(board), os.path.join(FIRMWARE, "UserParms.h")])
    return Env(raw, xt)


# ---- the core's arithmetic --------------------------------------------------


def duty_sample_max(fcy, fpwm, trig_tcy, deadtime_ns, min_on_ns):
    """mc_derived.h MC_DUTY_SAMPLE_MAX: the largest duty (counts) of a measured
    phase that leaves its low-side switch on min_on_ns before the ADC trigger,
    trig_tcy after the centre-aligned period's midpoint, and still on at it."""
    ptper = fcy // fpwm / 2.0 - 1.0
    dt = deadtime_ns * 1e-9 * fcy
    on = min_on_ns * 1e-9 * fcy
    return int(min(2.0 * (ptper - trig_tcy) - 2.0, 2.0 * (ptper + trig_tcy - dt - on)))


def q15_round(x):
    """q15.h Q15(x): range [-1, 1], x*32768 rounded half away from zero, 1.0 -> 32767."""
    if not (-1.0 <= x <= 1.0):
        raise ValueError(f"Q15({x!r}) out of [-1, 1]")
    if x * 32768.0 >= 32767.5:
        return 32767
    return int(x * 32768.0 + (0.5 if x >= 0 else -0.5))


def shift_of(x, top=7):
    s = 0
    while s < top and x >= float(1 << s):
        s += 1
    return s


def mant_shift(x, top=7):
    s = shift_of(x, top)
    return q15_round(x / float(1 << s)), s


def _expneg(y):
    # SMC_EXPNEG_ of smc.h: the (3,3) Pade approximant of exp(-y).
    return (1.0 - y * (0.5 - y * (0.1 - y / 120.0))) / (1.0 + y * (0.5 + y * (0.1 + y / 120.0)))


class Derived:
    """Rows (name, engineering value, unit, Q15 integer or None, decoded value,
    note) and failed checks (parameter, message)."""

    def __init__(self):
        self.rows, self.failures, self.values = [], [], {}

    def row(self, name, eng, unit, q=None, decoded=None, note=""):
        self.rows.append((name, eng, unit, q, decoded, note))
        self.values[name] = q if q is not None else eng

    def check(self, param, cond, msg):
        if not cond:
            self.failures.append((param, msg))
        return cond


def derive_core(env):
    """Replays mc_derived.h / SMC_PARAMS_INIT / mc.c for the macros in env."""
    d = Derived()
    g = env.get
    fcy, fpwm = g("BOARD_FCY_HZ"), g("PWM_FREQUENCY_HZ")
    i_fs, vbus_fs, vbus_nom = g("BOARD_I_FULLSCALE_A"), g("BOARD_VBUS_FULLSCALE_V"), g("BOARD_VBUS_NOMINAL_V")
    loop_hz = g("MC_SPEED_LOOP_HZ")
    pp = g("MOTOR_POLE_PAIRS")
    fs_rpm = g("MC_SPEED_FULLSCALE_RPM")
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

    def q_scaled(name, x, fs, unit, scale, note):
        """A row for x as Q15 of the full scale fs (checked, then saturated like Q15())."""
        d.check(name, -1.0 <= x / fs <= 1.0, f"out of the {scale} Q15 range")
        q = q15_round(max(-1.0, min(1.0, x / fs)))
        d.row(name, x, unit, q, q / 32768.0 * fs, note)

    def q_rpm(name, rpm, note=""):
        q_scaled(name, rpm, fs_rpm, "rpm", "speed", note)

    def q_amp(name, a, note=""):
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
    d.check("MC_SPEED_RAMP_RPM_PER_S", 1.0 <= step < 32767.0, "must give 1..32767 Q15 counts per speed-loop run")
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
    q_amp("MOTOR_RAMP_CURRENT_A", i_ramp, "Iq during the open-loop ramp")
    damp, damp_max = g("MOTOR_OL_DAMP_S"), g("MC_OL_DAMP_MAX_DEG")
    d.check("MOTOR_OL_DAMP_S", 0.0 <= damp and damp * fpwm <= 1000.0, "must be 0..1000 PWM periods")
    d.check("MC_OL_DAMP_MAX_DEG", 0.0 <= damp_max <= 90.0, "must be 0..90 deg")
    d.row("MOTOR_OL_DAMP_S", damp, "s", int(damp * fpwm * 16.0 + 0.5), None,
          "open-loop damping, MC_OL_DAMP_K (Q4 periods)")

    # bus
    uv, ov = g("MC_VBUS_UNDERVOLTAGE_V"), g("MC_VBUS_OVERVOLTAGE_V")
    d.check("MC_VBUS_UNDERVOLTAGE_V", 0.0 < uv < vbus_nom, "must be in (0, BOARD_VBUS_NOMINAL_V)")
    d.check("MC_VBUS_OVERVOLTAGE_V", vbus_nom < ov < vbus_fs, "must be in (BOARD_VBUS_NOMINAL_V, BOARD_VBUS_FULLSCALE_V)")
    vlim = g("MC_VOLTAGE_LIMIT_FRACTION")
    d.check("MC_VOLTAGE_LIMIT_FRACTION", 0.5 < vlim <= 1.0, "must be in (0.5, 1]")
    q = q15_round(vlim)
    d.row("MC_VOLTAGE_LIMIT_FRACTION", vlim * v_fs, "V", q, q / 32768.0 * v_fs, "largest |V|, phase peak")

    # current PI
    kp, ki = g("MOTOR_CURRENT_KP_V_PER_A"), g("MOTOR_CURRENT_KI_V_PER_AS")
    kp_ = kp * i_fs / v_fs
    ki_ = ki * ts * i_fs / v_fs
    if d.check("MOTOR_CURRENT_KP_V_PER_A", 0.0 <= kp_ < 128.0, "Kp * I_FS / V_FS must be in [0, 128)"):
        m, s = mant_shift(kp_)
        d.row("MOTOR_CURRENT_KP_V_PER_A", kp, "V/A", m, m * (1 << s) / 32768.0 * v_fs / i_fs, f"MC_CUR_KP, shift {s}")
    if d.check("MOTOR_CURRENT_KI_V_PER_AS", 0.0 <= ki_ < 1.0, "Ki * Ts * I_FS / V_FS must be in [0, 1)"):
        q = q15_round(ki_)
        d.row("MOTOR_CURRENT_KI_V_PER_AS", ki, "V/(A s)", q, q / 32768.0 * v_fs / i_fs / ts, "MC_CUR_KI, per period")
    # speed PI
    kp, ki = g("MOTOR_SPEED_KP_A_PER_RPM"), g("MOTOR_SPEED_KI_A_PER_RPM_S")
    kp_ = kp * fs_rpm / i_fs
    ki_ = ki / loop_hz * fs_rpm / i_fs
    if d.check("MOTOR_SPEED_KP_A_PER_RPM", 0.0 <= kp_ < 128.0, "Kp * speed FS / I_FS must be in [0, 128)"):
        m, s = mant_shift(kp_)
        d.row("MOTOR_SPEED_KP_A_PER_RPM", kp, "A/rpm", m, m * (1 << s) / 32768.0 * i_fs / fs_rpm, f"MC_SPD_KP, shift {s}")
    if d.check("MOTOR_SPEED_KI_A_PER_RPM_S", 0.0 <= ki_ < 1.0, "Ki / loop rate * speed FS / I_FS must be in [0, 1)"):
        q = q15_round(ki_)
        d.row("MOTOR_SPEED_KI_A_PER_RPM_S", ki, "A/(rpm s)", q, q / 32768.0 * i_fs / fs_rpm * loop_hz, "MC_SPD_KI, per speed-loop run")

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
    d.check("MOTOR_LOCK_TIME_S", 1.0 <= t_lock * fpwm <= 65000.0, "must be 1..65000 PWM periods")
    lp = int(t_lock * fpwm + 0.5)
    d.row("MOTOR_LOCK_TIME_S", t_lock, "s", lp, lp * ts, "MC_LOCK_PERIODS (periods)")
    t_ramp = g("MOTOR_RAMP_TIME_S")
    periods = t_ramp * fpwm
    inc_ = ramp_end * pp / 60.0 * ts * 4294967296.0 / periods if periods > 0 else 0.0
    d.check("MOTOR_RAMP_END_RPM", est_min <= ramp_end < n_nom, "must be in [MC_ESTIMATOR_MIN_RPM, MOTOR_SPEED_NOMINAL_RPM)")
    d.check("MOTOR_RAMP_TIME_S", 100.0 <= periods <= 4.0e6, "must be 100..4e6 PWM periods")
    d.check("MOTOR_RAMP_TIME_S", inc_ >= 8.0, "ramp too slow for the 32-bit angle (step increment < 8)")
    inc = int(inc_ + 0.5)
    end = inc * int(periods + 0.5)
    d.row("MOTOR_RAMP_TIME_S", t_ramp, "s", int(periods + 0.5), int(periods + 0.5) * ts, "ramp periods")
    d.row("MOTOR_RAMP_END_RPM", ramp_end, "rpm", end, end * fpwm * 60.0 / (4294967296.0 * pp), "MC_RAMP_STEP_END (32-bit angle step)")
    accel = inc * fpwm * fpwm * 60.0 / (4294967296.0 * pp)
    d.row("ramp acceleration", ramp_end / t_ramp if t_ramp else 0.0, "rpm/s", inc, accel, "MC_RAMP_STEP_INC per period")

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
    if y > 1.0:
        return d
    f = _expneg(y)
    gg = (1.0 - f) / r * v_fs / i_fs  # G in V_FS units
    ge = gg * e_ratio  # ... and in the core's E_FS units
    ks = kslide_v / v_fs
    me = band_a / i_fs
    kz = ks / e_ratio / me
    d.row("F (AN1078 Eq. 2: 1 - Ts R/L)", 1.0 - y, "", None, None, "the Euler form of AN1078")
    q = q15_round(f)
    d.row("smc F = exp(-Ts R/L)", f, "", q, q / 32768.0, "the core's exact discretisation (Pade 3,3)")
    d.row("G (AN1078 Eq. 2: Ts/L)", ts / l, "A/(V period)", None, None, "in amps per volt")
    d.row("G = (1-F)/R * V_FS/I_FS", gg, "I_FS/V_FS", None, None, "in the core's current and voltage scales")
    d.check("smc_G", 1e-4 <= ge < 128.0, "G * 2 V_FS / I_FS must be in [1e-4, 128)")
    m, s_ = mant_shift(ge, 7)
    d.row("smc G = (1-F)/R * 2V_FS/I_FS", ge, "I_FS/E_FS", m, m * (1 << s_) / 32768.0, f"g_shift {s_}")
    if d.check("MOTOR_SMC_GAIN_V", 0.0 < ks < e_ratio, "smc: Kslide must be in (0, 2) of V_FS"):
        q = q15_round(ks / e_ratio)
        d.row("MOTOR_SMC_GAIN_V", kslide_v, "V", q, q / 32768.0 * v_fs * e_ratio, "Kslide, Q15 of E_FS = 2 V_FS")
    if d.check("MOTOR_SMC_LINEAR_BAND_A", 1.0 / 32768.0 <= me < 1.0, "smc: MaxSMCError must be in [1 LSB, 1)"):
        q = q15_round(me)
        d.row("MOTOR_SMC_LINEAR_BAND_A", band_a, "A", q, q / 32768.0 * i_fs, "MaxSMCError")
    if d.check("MOTOR_SMC_LINEAR_BAND_A", kz < 32768.0, "smc: Kslide / MaxSMCError must be below 32768"):
        m, s_ = mant_shift(kz, 15)
        d.row("smc Kz = Kslide / MaxSMCError", kz, "E_FS/I_FS", m, m * (1 << s_) / 32768.0, f"kz_shift {s_}")
    c = ge * kz
    d.row("smc loop gain c = G Kz", c, "", None, None,
          "linear band dead-beat at c = F; relay (chattering) mode above 1 + F")
    kpw = TWO_PI * w_fs * ts
    if d.check("MC_SPEED_FULLSCALE_RPM", kpw < 1.0, "smc: 2 pi omega_fs Ts must be below 1"):
        q = q15_round(kpw)
        d.row("smc K per unit speed", kpw, "rad/period", q, q / 32768.0, "Kslf at full-scale speed (AN1078 Eq. 7)")
    f_min = est_min * pp / 60.0
    ok = d.check("MC_ESTIMATOR_MIN_RPM", 0.0 < f_min < w_fs and TWO_PI * f_min * ts >= 1.0 / 32768.0,
                 "smc: min speed must be in (0, omega_fs)")
    if ok:
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
    # dead time
    dt = g("PWM_DEADTIME_NS") * 1e-9 * fcy
    d.check("PWM_DEADTIME_NS", 0.0 <= dt < 0.1 * duty_max, "must be below 10 % of the PWM period")
    # shunt window
    win = duty_sample_max(fcy, fpwm, g("PWM_ADC_TRIGGER_TCY"), g("PWM_DEADTIME_NS"), g("BOARD_SHUNT_MIN_ON_NS"))
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


def format_table(d, title):
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
