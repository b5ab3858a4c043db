# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Unit tests of tools/tune: derivations vs hand calculations, bad input, the
field-weakening table, the C probe that reads the core's headers, the --check
round trip, and the generated headers against the core (they compile, and the
committed ones are what the tool writes, byte for byte).

Run: .venv/bin/python -m unittest -v test_tune_unit   (from test/tune; CTest does it)
"""

from __future__ import annotations

import cmath
import glob
import math
import os
import shutil
import subprocess
import tempfile
import tomllib
import unittest
from pathlib import Path

from tune.motortune import derive, describe, generate, probe
from tune.motortune.derive import Infeasible, Tuning
from tune.motortune.describe import Description
from tune.motortune.units import InputError

REPO = probe.REPO
TUNE = str(REPO / "tools" / "tune" / "tune")
EXAMPLES = REPO / "tools" / "tune" / "examples"
MOTORS = REPO / "firmware" / "motors"

# name of the example -> (the profile tools/tune gives on its own, without [tuning]; board)
EXAMPLE_PROFILES = {"hurst": ("hurst075", "mclv"), "hurst300": ("hurst_long", "mclv"),
                    "hispeed": ("hs2p", "mchv"), "lowl": ("lowl", "mclv")}
# the committed profile of each example (with its [tuning]): firmware/motors/motor_<example>.h

HURST_TOML = """\
name = "hurst_t"
board = "mclv"
pwm_frequency = "20 kHz"
[motor]
pole_pairs = 5
resistance = "5.34 ohm"
resistance_kind = "line-to-line"
inductance = "3.84 mH"
inductance_kind = "line-to-line"
back_emf = "7.3 V/krpm"
back_emf_kind = "peak line-to-line"
rated_current = "1.64 A"
current_kind = "peak"
rated_speed = "2700 rpm"
peak_current = "3.0 A"
inertia = "7.5e-6 kg m^2"
[application]
max_speed = "5300 rpm"
fw_load_current = "0.1 A"
"""


def scratch() -> str:
    base = os.environ.get("TUNE_SCRATCH")
    if base:
        os.makedirs(base, exist_ok=True)
    return tempfile.mkdtemp(prefix="tune_", dir=base)


def run_tune(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([TUNE, *args], capture_output=True, text=True)


def own_profile(name: str) -> Path:
    """The profile tools/tune gives on its own for an example (EXAMPLE_PROFILES' names): the
    build tree's (TUNE_PROFILES, test/tune/CMakeLists.txt), else written here."""
    built = Path(os.environ.get("TUNE_PROFILES", "/nonexistent")) / f"motor_{name}.h"
    if built.exists():
        return built
    ex = next(e for e, (n, _) in EXAMPLE_PROFILES.items() if n == name)
    out = Path(scratch()) / f"motor_{name}.h"
    r = run_tune("--no-tuning", "--no-compile", "--name", name, "-o", str(out), str(EXAMPLES / f"{ex}.toml"))
    assert r.returncode == 0, r.stderr
    return out


def desc_from(text: str) -> Description:
    return describe.parse(tomllib.loads(text))


def tool_only(text: str, extra: str = "") -> str:
    """A description without its [tuning] table (what the tool derives on its own), with
    the top-level line extra (e.g. a pwm_frequency) added after its board line."""
    if "\n[tuning]" in text:
        head, _, rest = text.partition("\n[tuning]")
        nxt = rest.find("\n[")
        text = head + ("\n" + rest[nxt + 1:] if nxt >= 0 else "\n")
    if extra:
        text = text.replace("\nboard = ", f"\n{extra}\nboard = ", 1)
    return text


def measured(fmt: str, *a: object) -> None:
    print("measured: " + fmt % a)


def read(path: str | Path) -> str:
    return Path(path).read_text(encoding="utf-8")


def core_of(path: str | Path, board: str) -> probe.Profile:
    """The core's values for a header, through the probe (what --check prints)."""
    return probe.profile(read(path), board, str(path))


def rows_of(prof: probe.Profile) -> dict[str, probe.Row]:
    return {r.name: r for r in prof.out.rows}


def fw_rows(prof: probe.Profile) -> list[probe.Row]:
    return [r for r in prof.out.rows if r.name.startswith("FW Id[")]


def setUpModule() -> None:
    try:
        probe.find_cc()
    except probe.NoCompiler as e:  # tools/tune reads the core through the C compiler
        raise unittest.SkipTest(str(e)) from None


class HurstHandCalculation(unittest.TestCase):
    """AN1078's Hurst (5.34 ohm, 3.84 mH line to line, 20 kHz) worked by hand."""

    d: Description
    t: Tuning
    dir: str
    h: str
    core: probe.Profile

    @classmethod
    def setUpClass(cls) -> None:
        cls.d = desc_from(HURST_TOML)
        cls.t = derive.derive(cls.d)
        cls.dir = scratch()
        cls.h = os.path.join(cls.dir, "motor_hurst_t.h")
        toml = os.path.join(cls.dir, "hurst_t.toml")
        Path(toml).write_text(HURST_TOML, encoding="utf-8")
        r = run_tune("-o", cls.h, toml)
        assert r.returncode == 0, r.stderr
        cls.core = core_of(cls.h, "mclv")

    @classmethod
    def tearDownClass(cls) -> None:
        shutil.rmtree(cls.dir, ignore_errors=True)

    def row(self, name: str) -> probe.Row:
        rows = rows_of(self.core)
        if name not in rows:
            self.fail(f"--check has no row {name}")
        return rows[name]

    def test_line_to_line_readings_should_be_halved_to_per_phase_values(self) -> None:
        self.assertAlmostEqual(self.d.r_ph, 2.67, places=12)
        self.assertAlmostEqual(self.d.l_ph, 1.92e-3, places=15)

    def test_observer_F_and_G_should_match_an1078_equation_3(self) -> None:
        ts = 1.0 / 20000.0
        f_euler = 1.0 - ts * 2.67 / 1.92e-3  # AN1078 Eq. 3: 0.9304 (0.930469 unrounded)
        self.assertAlmostEqual(self.row("F (AN1078 Eq. 2: 1 - Ts R/L)").eng, f_euler, places=12)
        self.assertAlmostEqual(f_euler, 0.9305, places=4)
        self.assertAlmostEqual(self.row("G (AN1078 Eq. 2: Ts/L)").eng, 0.0260417, places=7)  # Eq. 3: 0.026
        # The core discretises exactly: F = exp(-Ts R/L) (smc.h: a (3,3) Pade approximant),
        # G = (1 - F)/R, stored in the units of its back-EMF scale E_FS = 2 V_FS per I_FS.
        f = math.exp(-ts * 2.67 / 1.92e-3)
        g = (1.0 - f) / 2.67 * (24.0 / math.sqrt(3.0)) / 4.4
        ge = 2.0 * g
        r = self.row("smc F = exp(-Ts R/L)")
        self.assertAlmostEqual(r.eng, f, places=9)
        self.assertEqual(r.q, round(f * 32768))
        self.assertAlmostEqual(self.row("G = (1-F)/R * V_FS/I_FS").eng, g, places=9)
        r = self.row("smc G = (1-F)/R * 2V_FS/I_FS")
        self.assertAlmostEqual(r.eng, ge, places=9)
        self.assertEqual(r.q, round(ge * 32768))  # ge < 1: shift 0
        measured("Hurst F Euler %.6f (AN1078 0.9304), core F %.6f = Q15 %d, G Ts/L %.6f A/V (AN1078 "
                 "0.026), core G %.6f V_FS/I_FS, in E_FS units %.6f = Q15 %d", f_euler, f, round(f * 32768),
                 ts / 1.92e-3, g, ge, round(ge * 32768))

    def test_kslide_should_be_the_limited_back_emf_with_margin_and_the_band_dead_beat(self) -> None:
        v_fs = 24.0 / math.sqrt(3.0)
        e_top = 7.3 / math.sqrt(3.0) * 5.3  # 22.34 V at 5300 rpm, above what the bus can apply
        e_seen = min(e_top, 0.95 * v_fs)
        ks = min(1.5 * e_seen, 0.97 * v_fs)
        self.assertAlmostEqual(self.t["MOTOR_SMC_GAIN_V"], ks, delta=0.01)
        ts = 5e-5
        f = math.exp(-ts * 2.67 / 1.92e-3)
        band = ks * (1.0 - f) / 2.67 / f
        self.assertAlmostEqual(self.t["MOTOR_SMC_LINEAR_BAND_A"], band, delta=0.001)
        c = self.row("smc loop gain c = G Kz").eng
        self.assertAlmostEqual(c, f, delta=0.01 * f)  # dead-beat: c = F within the rounding
        measured("Kslide %.3f V (hand %.3f), band %.4f A (hand %.4f), loop gain c %.4f vs F %.4f",
                 self.t["MOTOR_SMC_GAIN_V"], ks, self.t["MOTOR_SMC_LINEAR_BAND_A"], band, c, f)

    def test_current_pi_should_cancel_the_winding_pole(self) -> None:
        wc = self.t["MOTOR_CURRENT_LOOP_BW_RAD_S"]
        self.assertLessEqual(wc, math.radians(20.0) / (1.5 * 5e-5))  # 70 deg phase margin
        # noise: Kp x one 10-bit ADC count (8.8 A / 1024) within 2 % of the back-EMF at the lowest speed
        e_min = 7.3 / math.sqrt(3) * self.t["MOTOR_SPEED_MIN_RPM"] / 1000.0
        self.assertLessEqual(self.t["MOTOR_CURRENT_KP_V_PER_A"] * 8.8 / 1024, 0.02 * e_min + 1e-9)
        self.assertGreater(self.t["MOTOR_CURRENT_KP_V_PER_A"] * 8.8 / 1024, 0.019 * e_min)
        self.assertAlmostEqual(self.t["MOTOR_CURRENT_KP_V_PER_A"] / self.t["MOTOR_CURRENT_KI_V_PER_AS"],
                               1.92e-3 / 2.67, delta=1e-3 * 1.92e-3 / 2.67)
        self.assertAlmostEqual(self.t["MOTOR_CURRENT_KP_V_PER_A"], 1.92e-3 * wc, delta=1e-3 * 1.92e-3 * wc)
        # Q15 in the core: Kp * I_FS / V_FS as mantissa and shift, Ki * Ts * I_FS / V_FS.
        kp_ = self.t["MOTOR_CURRENT_KP_V_PER_A"] * 4.4 / (24.0 / math.sqrt(3.0))
        s = 0
        while kp_ >= 2 ** s:
            s += 1
        kp_q = self.row("MOTOR_CURRENT_KP_V_PER_A").q
        self.assertEqual(kp_q, round(kp_ / 2 ** s * 32768))
        measured("current loop wc %.0f rad/s: Kp %.4g V/A, Ki %.5g V/(A s), Q15 Kp %d << %d",
                 wc, self.t["MOTOR_CURRENT_KP_V_PER_A"], self.t["MOTOR_CURRENT_KI_V_PER_AS"], kp_q, s)

    def test_speed_pi_should_keep_its_margin_down_to_half_the_inertia(self) -> None:
        # The loop as the core runs it, sampled at the speed-loop rate: the PI on the speed
        # error, Kt Iq / (J s) to the rotor, the estimate through the one-pole filter
        # y += a (x - y), a = 2 pi fc / loop, and 1.5 loop periods of delay. The crossover is
        # found on the exact |L| (the tool bisects on the phase at k x ws).
        psi = 7.3 / math.sqrt(3.0) / (1000.0 * 2 * math.pi / 60.0 * 5)
        kt = 1.5 * 5 * psi
        loop = probe.board("mclv").loop_hz
        kp = self.t["MOTOR_SPEED_KP_A_PER_RPM"] * 60.0 / (2 * math.pi)  # A s/rad
        ki = self.t["MOTOR_SPEED_KI_A_PER_RPM_S"] * 60.0 / (2 * math.pi)
        a = 2 * math.pi * self.t["MC_SPEED_FILTER_HZ"] / loop

        def loop_gain(w: float, j: float) -> complex:
            s_ = 1j * w
            z1 = cmath.exp(-s_ / loop)
            return (kt * (kp + ki / s_) / (j * s_) * a / (1 - (1 - a) * z1)
                    * cmath.exp(-1.5 * s_ / loop))

        def margin(j: float) -> tuple[float, float]:
            lo, hi = 1.0, 1e4  # |L| falls through 1 once on this range
            for _ in range(80):
                mid = math.sqrt(lo * hi)
                lo, hi = (mid, hi) if abs(loop_gain(mid, j)) > 1.0 else (lo, mid)
            return lo, 180.0 + math.degrees(cmath.phase(loop_gain(lo, j)))

        w1, pm1 = margin(7.5e-6)
        w05, pm05 = margin(0.5 * 7.5e-6)
        w20, pm20 = margin(20 * 7.5e-6)
        self.assertGreaterEqual(pm05, 36.0)  # 40 deg at twice the design crossover by the tool's rule
        self.assertGreaterEqual(pm1, 55.0)
        self.assertGreaterEqual(pm20, 25.0)
        self.assertLessEqual(w1, 2 * math.pi * loop / 20.0)  # the sampled-loop cap
        self.assertAlmostEqual(ki / kp * 8.0, kp * kt / 7.5e-6, delta=0.01 * kp * kt / 7.5e-6)  # zero ws/8
        measured("speed loop: crossover %.0f / %.0f / %.1f rad/s, phase margin %.1f / %.1f / %.1f deg at "
                 "1 / 0.5 / 20 x the stated J (Kp %.4g A/rpm, Ki %.4g A/(rpm s))", w1, w05, w20, pm1, pm05,
                 pm20, self.t["MOTOR_SPEED_KP_A_PER_RPM"], self.t["MOTOR_SPEED_KI_A_PER_RPM_S"])

    def test_nominal_speed_should_be_where_the_back_emf_meets_the_bus(self) -> None:
        # |V|^2 = (w L Iq)^2 + (R Iq + w psi)^2 = V^2 at Id = 0: a quadratic in w, solved here
        # directly (the tool bisects on the speed).
        # The budget is the shunt window's, below the 0.95 circle: the measured phases' duties
        # stay at or below 2 (PTPER + trigger - dead time - settling) = 2 (999 + 80 - 80 - 120)
        # = 1758 of 2000 counts (MC_DUTY_SAMPLE_MAX).
        r, l, iq = 2.67, 1.92e-3, 0.1
        psi = 7.3 / math.sqrt(3.0) / (1000.0 * 2 * math.pi / 60.0 * 5)
        v = 1758.0 / 2000.0 * 24.0 / math.sqrt(3.0) * (1.0 - 0.05 - 2e-6 * 20000)
        a, b, c = (l * iq) ** 2 + psi ** 2, 2 * r * iq * psi, (r * iq) ** 2 - v * v
        w = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
        n = w / (2 * math.pi / 60.0) / 5
        self.assertAlmostEqual(self.t.n_bus, n, delta=0.01)
        self.assertEqual(self.t["MOTOR_SPEED_NOMINAL_RPM"], math.floor(n / 10.0) * 10.0)
        measured("Hurst nominal speed %.1f rpm (hand %.1f rpm, AN1078 hand-tuned 2700)", self.t.n_bus, n)

    def test_limits_should_respect_the_board(self) -> None:
        self.assertLess(self.t["MOTOR_OVERCURRENT_A"], 0.9 * 4.4 + 1e-9)
        self.assertLess(self.t["MOTOR_CURRENT_MAX_A"], self.t["MOTOR_OVERCURRENT_A"])
        self.assertLessEqual(self.t["MOTOR_CURRENT_MAX_A"], 1.64)
        self.assertEqual(self.core.refused, [])


class FieldWeakeningTable(unittest.TestCase):
    def check_table(self, t: Tuning) -> float:
        d = t.desc
        tab, speeds = t.fw_table, t.fw_speeds
        self.assertEqual(len(tab), 16)
        self.assertEqual(tab[0], 0.0)
        for k in range(1, 16):
            self.assertLessEqual(tab[k], tab[k - 1], "monotone")
        psi, r, l, pp, iq = t.psi, d.r_ph, d.l_ph, d.pole_pairs, t.i_load
        worst = 0.0
        for n, i_d in zip(speeds, tab, strict=True):
            self.assertLessEqual(math.hypot(i_d, iq), t.i_peak + 1e-9, "current limit")
            self.assertGreater(i_d, -t.i_fs, "inside the current scale")
            w = n * 2 * math.pi / 60.0 * pp
            v = math.hypot(r * i_d - w * l * iq, r * iq + w * (psi + l * i_d))
            # the table is rounded to 1 mA: the voltage may exceed the budget by that much
            dv = math.hypot(r, w * l) * 0.0005
            self.assertLessEqual(v, t.v_ss + dv + 1e-9, f"voltage at {n:.0f} rpm")
            if i_d < 0.0:  # smallest |Id|: 2 mA less field weakening is over the budget
                i2 = i_d + 0.002
                v2 = math.hypot(r * i2 - w * l * iq, r * iq + w * (psi + l * i2))
                self.assertGreater(v2, t.v_ss, f"Id at {n:.0f} rpm is not the smallest")
            worst = max(worst, v - t.v_ss)
        self.assertEqual(speeds[-1], t["MOTOR_SPEED_FW_MAX_RPM"])
        return worst

    def test_hurst_table_should_be_monotone_within_limits_and_reach_the_top_speed(self) -> None:
        t = derive.derive(desc_from(HURST_TOML))
        worst = self.check_table(t)
        self.assertEqual(t["MOTOR_SPEED_FW_MAX_RPM"], 5300.0)
        measured("Hurst FW table: Id %.3f A at %.0f rpm, worst voltage over budget %.4f V",
                 t.fw_table[-1], t.fw_speeds[-1], worst)

    def test_every_example_table_should_be_monotone_within_limits(self) -> None:
        for ex in EXAMPLE_PROFILES:
            with self.subTest(ex):
                self.check_table(derive.derive(describe.load(str(EXAMPLES / f"{ex}.toml"))))

    def test_no_field_weakening_when_the_bus_reaches_the_top_speed(self) -> None:
        t = derive.derive(describe.load(str(EXAMPLES / "hispeed.toml")))
        self.assertEqual(t["MOTOR_SPEED_NOMINAL_RPM"], t["MOTOR_SPEED_FW_MAX_RPM"])
        self.assertEqual(t.fw_table, [0.0] * 16)
        self.assertGreater(t.n_bus, 17000.0)

    def test_a_speed_the_bus_cannot_reach_should_be_an_error_naming_max_speed(self) -> None:
        with self.assertRaises(Infeasible) as cm:
            derive.derive(desc_from(HURST_TOML.replace('"5300 rpm"', '"9000 rpm"')))
        self.assertEqual(cm.exception.field, "application.max_speed")
        self.assertIn("even with field weakening", str(cm.exception))
        # the default load (a quarter of the Iq limit) cannot reach 5300 rpm either
        with self.assertRaises(Infeasible):
            derive.derive(desc_from(HURST_TOML.replace('fw_load_current = "0.1 A"\n', "")))

    def test_hurst300_on_the_mclv_should_be_derated_not_refused(self) -> None:
        t = derive.derive(describe.load(str(EXAMPLES / "hurst300.toml")))
        self.assertTrue(t.warnings and "derated" in t.warnings[0])
        self.assertLess(t["MOTOR_CURRENT_MAX_A"], 4.88)
        self.assertLessEqual(t["MOTOR_OVERCURRENT_A"], 0.9 * 4.4 + 1e-9)
        self.assertLessEqual(t["MOTOR_CURRENT_MAX_A"], 0.9 * t["MOTOR_OVERCURRENT_A"] + 1e-9)
        measured("Hurst300 on the MCLV: Iq limit %.3g A of the rated 4.88 A (%.0f %%), trip %.3g A",
                 t["MOTOR_CURRENT_MAX_A"], 100 * t["MOTOR_CURRENT_MAX_A"] / 4.88, t["MOTOR_OVERCURRENT_A"])


class WithoutInertia(unittest.TestCase):
    def test_no_inertia_should_give_the_safe_defaults_and_a_valid_profile(self) -> None:
        text = HURST_TOML.replace('inertia = "7.5e-6 kg m^2"\n', "")
        t = derive.derive(desc_from(text))
        self.assertEqual(t["MOTOR_LOCK_TIME_S"], 0.25)
        self.assertEqual(t["MOTOR_RAMP_TIME_S"], 1.0)
        kp = t["MOTOR_SPEED_KP_A_PER_RPM"]
        self.assertAlmostEqual(kp, 1.64 / (0.4 * 5300.0), delta=0.005 * kp)
        self.assertAlmostEqual(t["MOTOR_SPEED_KI_A_PER_RPM_S"], 5.0 * kp, delta=0.01 * kp)
        d = scratch()
        try:
            p = os.path.join(d, "m.toml")
            Path(p).write_text(text, encoding="utf-8")
            h = os.path.join(d, "motor_m.h")
            r = run_tune("-o", h, p)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(core_of(h, "mclv").refused, [])
        finally:
            shutil.rmtree(d, ignore_errors=True)


class StartLoad(unittest.TestCase):
    """application.start_load sizes the start-up current; a load it cannot start is refused."""

    def test_a_start_load_should_size_the_ramp_current_at_60_percent_of_its_torque(self) -> None:
        t = derive.derive(desc_from(HURST_TOML + 'start_load = "0.05 N m"\n'))
        kt = t.kt
        i = t["MOTOR_RAMP_CURRENT_A"]
        measured("start load 50 mN m, Kt %.2f mN m/A: ramp current %.3f A, lock %.3f A", kt * 1e3, i,
                 t["MOTOR_LOCK_CURRENT_A"])
        self.assertAlmostEqual(0.6 * kt * i, 0.05, delta=0.002)
        self.assertEqual(t["MOTOR_LOCK_CURRENT_A"], i)
        self.assertAlmostEqual(t["MOTOR_START_LOAD_NM"], 0.05, delta=1e-6)

    def test_without_a_start_load_the_claim_should_be_60_percent_of_the_default_current(self) -> None:
        t = derive.derive(desc_from(HURST_TOML))
        self.assertAlmostEqual(t["MOTOR_START_LOAD_NM"], 0.6 * t.kt * t["MOTOR_RAMP_CURRENT_A"], delta=1e-4)

    def test_a_light_start_load_should_keep_the_default_current(self) -> None:
        light = derive.derive(desc_from(HURST_TOML + 'start_load = "1 mN m"\n'))
        none = derive.derive(desc_from(HURST_TOML))
        self.assertEqual(light["MOTOR_RAMP_CURRENT_A"], none["MOTOR_RAMP_CURRENT_A"])

    def test_a_start_load_beyond_the_current_limit_should_be_refused_naming_it(self) -> None:
        d = scratch()
        try:
            p = os.path.join(d, "m.toml")
            Path(p).write_text(HURST_TOML + 'start_load = "0.2 N m"\n', encoding="utf-8")
            r = run_tune("-o", os.path.join(d, "motor_m.h"), p)
            measured("error line: %s", r.stderr.strip())
            self.assertNotEqual(r.returncode, 0)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1)
            self.assertIn("application.start_load", r.stderr)
            self.assertIn("cannot start", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "motor_m.h")))
        finally:
            shutil.rmtree(d, ignore_errors=True)

    def test_a_small_inductance_should_raise_the_lock_current_to_what_the_dead_time_measurement_needs(
            self) -> None:
        # 0.17 mH per phase on 24 V: the dead-time band Vbus / (12 L fpwm) is 0.59 A, the lock's
        # measurement (mc_derived.h, MC_DTM_LOCK_BANDS through the probe) needs 2.31 of it.
        low_l = HURST_TOML.replace('"3.84 mH"', '"0.34 mH"').replace('"5300 rpm"', '"2500 rpm"')
        t = derive.derive(desc_from(low_l))
        band = 24.0 / (12.0 * 0.17e-3 * 20000.0)
        bands = probe.board("mclv").limits.dtm_lock_bands
        measured("L 0.17 mH: band %.3f A, lock current %.3f A (default 0.984 A)", band, t["MOTOR_LOCK_CURRENT_A"])
        self.assertAlmostEqual(bands, 1.5 / (0.75 * math.sqrt(3.0) / 2.0), places=12)
        self.assertGreaterEqual(t["MOTOR_LOCK_CURRENT_A"], bands * band)
        self.assertLess(t["MOTOR_LOCK_CURRENT_A"], bands * band * 1.01)
        with self.assertRaises(Infeasible) as e:
            derive.derive(desc_from(low_l.replace('rated_current = "1.64 A"', 'rated_current = "1.2 A"')))
        measured("error: %s", e.exception)
        self.assertIn("MC_DEADTIME_MEASURE", str(e.exception))

    def test_the_damping_should_give_its_ratio_at_the_stated_inertia(self) -> None:
        t = derive.derive(desc_from(HURST_TOML))
        wn = math.sqrt(5 * t.kt * t["MOTOR_RAMP_CURRENT_A"] / 7.5e-6)
        zeta = t["MOTOR_OL_DAMP_S"] * wn / 2.0
        measured("open-loop swing %.0f rad/s, MOTOR_OL_DAMP_S %.4f s: zeta %.3f", wn, t["MOTOR_OL_DAMP_S"], zeta)
        self.assertAlmostEqual(zeta, derive.OL_DAMP_ZETA, delta=0.01)
        no_j = derive.derive(desc_from(HURST_TOML.replace('inertia = "7.5e-6 kg m^2"\n', "")))
        self.assertNotIn("MOTOR_OL_DAMP_S", dict(no_j.by))


class CoreLimits(unittest.TestCase):
    """Derived values the core bounds (firmware/mc_derived.h MC_CHECK lines), reached by
    ordinary motors: each is rounded or held to the safe side of the core's limit, with a
    note, or refused naming the description's field; never a C macro the core rejects."""

    # lowl with 0.23025 mH and 1.5 A: the dead-time band Vbus / (12 L fpwm) is 0.4343 A, the
    # lock needs 2.31 of them, 1.0029 A; rounded to the nearest 3 digits that was 1.0 A
    LOWL_1A = (read(EXAMPLES / "lowl.toml").replace('"0.192 mH"', '"0.23025 mH"')
               .replace('rated_current = "3.0 A"', 'rated_current = "1.5 A"').replace('start_load = "0.05 N m"', ""))
    # hs2p on the MCHV at 40 kHz under a 1e-3 kg m^2 flywheel: 8 swings of the lock take 2 s
    # (80000 periods, the core counts 65000), 2 zeta / w of open-loop damping 44 ms (1780 periods)
    # (its ramp ends at 5000 rpm: the tool's 11300 rpm would need more than half the ramp
    # torque to reach in the 10 s the forced angle allows at 40 kHz, which the core refuses)
    HEAVY_40K = (tool_only(read(EXAMPLES / "hispeed.toml"), 'pwm_frequency = "40 kHz"')
                 .replace('"2.0e-5 kg m^2"', '"1e-3 kg m^2"') + '\n[application]\nmin_speed = "5000 rpm"\n')
    # the Hurst with 0.17 mH per phase: the dead-beat band Kslide G / F is 6 A, the MCLV reads 4.4 A
    LOW_L = HURST_TOML.replace('"3.84 mH"', '"0.34 mH"').replace('"5300 rpm"', '"2500 rpm"')
    # 20 ohm per phase: the noise-limited 3300 rad/s gives Ki Ts I_FS / V_FS = 1.05, beyond Q15
    HIGH_R = (HURST_TOML.replace('"5.34 ohm"', '"40 ohm"').replace('"3.84 mH"', '"4 mH"')
              .replace('"7.3 V/krpm"', '"20 V/krpm"').replace('"2700 rpm"', '"800 rpm"')
              .replace('"5300 rpm"', '"800 rpm"').replace('"1.64 A"', '"0.3 A"')
              .replace('peak_current = "3.0 A"\n', "").replace('fw_load_current = "0.1 A"\n', "")
              .replace('"7.5e-6 kg m^2"', '"2e-5 kg m^2"'))
    # the Hurst with 15 mH per phase: the ripple Vbus / (12 L fpwm) is 6.7 mA, 50 Q15 counts of
    # the 4.4 A scale, fewer than the dead time's 80 (the compensation's in-band slope >= 1)
    LARGE_L = HURST_TOML.replace('"3.84 mH"', '"30 mH"')
    # a 500 rpm motor: 1.5 x its top speed is a 1000 rpm scale, the stall detector's speed
    # error (UserParms.h) is 1500 rpm
    SLOW = (HURST_TOML.replace('"7.3 V/krpm"', '"30 V/krpm"').replace('"2700 rpm"', '"500 rpm"')
            .replace('max_speed = "5300 rpm"\n', "").replace('fw_load_current = "0.1 A"\n', "")
            .replace('"7.5e-6 kg m^2"', '"5e-5 kg m^2"'))

    def setUp(self) -> None:
        self.dir = scratch()

    def tearDown(self) -> None:
        shutil.rmtree(self.dir, ignore_errors=True)

    def generate(self, text: str, *opts: str) -> tuple[int, list[str], str]:
        """(exit code, stderr lines, the header's path): the tool run on text, compile check included."""
        p = os.path.join(self.dir, "m.toml")
        Path(p).write_text(text, encoding="utf-8")
        h = os.path.join(self.dir, "motor_m.h")
        r = run_tune(*opts, "-o", h, p)
        return r.returncode, r.stderr.strip().splitlines(), h

    def accepted_by_the_core(self, text: str, macro: str, board: str = "mclv") -> None:
        code, lines, h = self.generate(text)
        measured("%s: exit %d: %s", macro, code, " / ".join(lines))
        self.assertEqual(code, 0, lines)
        self.assertTrue(any(ln.startswith("tune: note: " + macro) for ln in lines), lines)
        self.assertEqual(core_of(h, board).refused, [])
        r = run_tune("--check", h)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_sig_up_should_never_round_below(self) -> None:
        for x in (1.0029, 1.0, 0.98400001, 2.3006, 123456.0, 4.4e-5):
            with self.subTest(x):
                self.assertGreaterEqual(derive.sig_up(x, 3), x)
                self.assertLess(derive.sig_up(x, 3), x * 1.01)
        self.assertEqual(derive.sig_up(1.0, 3), 1.0)

    def test_the_lock_current_should_round_up_to_what_the_dead_time_measurement_needs(self) -> None:
        t = derive.derive(desc_from(self.LOWL_1A))
        need = probe.board("mclv").limits.dtm_lock_bands * 24.0 / (12.0 * 0.23025e-3 * 20000.0)
        measured("lock current %.4g A, the measurement needs %.4f A", t["MOTOR_LOCK_CURRENT_A"], need)
        self.assertGreaterEqual(t["MOTOR_LOCK_CURRENT_A"], need)
        code, lines, h = self.generate(self.LOWL_1A)
        self.assertEqual(code, 0, lines)
        # the core's check (through the probe, without compiling mc.c) refuses the old 1.0 A
        text = read(h).replace(f"#define MOTOR_LOCK_CURRENT_A {t['MOTOR_LOCK_CURRENT_A']}",
                               "#define MOTOR_LOCK_CURRENT_A 1.0")
        Path(h).write_text(text, encoding="utf-8")
        r = run_tune("--check", h, "--no-compile")
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("MOTOR_LOCK_CURRENT_A: must be at least 2.31 dead-time bands", r.stderr)

    def test_the_lock_time_should_fit_the_cores_period_count(self) -> None:
        t = derive.derive(desc_from(self.HEAVY_40K))
        self.assertLessEqual(t["MOTOR_LOCK_TIME_S"] * 40000, 65000)
        self.accepted_by_the_core(self.HEAVY_40K, "MOTOR_LOCK_TIME_S", "mchv")

    def test_the_open_loop_damping_should_fit_the_cores_range(self) -> None:
        t = derive.derive(desc_from(self.HEAVY_40K))
        self.assertLessEqual(t["MOTOR_OL_DAMP_S"] * 40000, 1000)
        self.assertTrue(any(n.startswith("MOTOR_OL_DAMP_S") for n in t.limited), t.limited)

    def test_the_observer_band_should_stay_below_the_current_scale(self) -> None:
        t = derive.derive(desc_from(self.LOW_L))
        self.assertLess(t["MOTOR_SMC_LINEAR_BAND_A"], 4.4)
        self.accepted_by_the_core(self.LOW_L, "MOTOR_SMC_LINEAR_BAND_A")

    def test_the_current_ki_should_fit_q15_or_be_refused_naming_the_bandwidth(self) -> None:
        t = derive.derive(desc_from(self.HIGH_R))
        ki_ = t["MOTOR_CURRENT_KI_V_PER_AS"] * 5e-5 * 4.4 / (24.0 / math.sqrt(3.0))
        measured("20 ohm: wc %.0f rad/s, Ki %.5g V/(A s) = %.3f of the core's Q15 range",
                 t["MOTOR_CURRENT_LOOP_BW_RAD_S"], t["MOTOR_CURRENT_KI_V_PER_AS"], ki_)
        self.assertLess(ki_, 1.0)
        self.assertAlmostEqual(t["MOTOR_CURRENT_KP_V_PER_A"] / t["MOTOR_CURRENT_KI_V_PER_AS"], 2e-3 / 20.0,
                               delta=1e-3 * 2e-3 / 20.0)  # the zero still cancels the winding pole
        self.accepted_by_the_core(self.HIGH_R, "MOTOR_CURRENT_LOOP_BW_RAD_S")
        # a bandwidth the user gives is not changed: the core's check refuses it, named by it
        code, lines, _ = self.generate(self.HIGH_R + 'current_bandwidth = "4000 rad/s"\n')
        measured("error line: %s", lines[0] if lines else "")
        self.assertEqual(code, 1, lines)
        self.assertEqual(len(lines), 1)
        self.assertIn(": application.current_bandwidth: gives MOTOR_CURRENT_KI_V_PER_AS", lines[0])
        self.assertIn("firmware/mc_derived.h:", lines[0])

    def test_a_pwm_rate_the_boards_voltage_scaling_cannot_take_should_name_pwm_frequency(self) -> None:
        # 40 kHz on the MCLV: 1000 duty counts put MC_VAPP_K at 42620, beyond int16
        with self.assertRaises(InputError) as cm:
            derive.derive(desc_from(HURST_TOML.replace('"20 kHz"', '"40 kHz"')))
        measured("error: %s", cm.exception)
        self.assertEqual(cm.exception.field, "pwm_frequency")
        self.assertIn("BOARD_VBUS_FULLSCALE_V", str(cm.exception))

    def test_a_large_inductance_should_get_the_narrowest_dead_time_band_the_core_takes(self) -> None:
        t = derive.derive(desc_from(self.LARGE_L))
        self.assertGreater(t["MC_DEADTIME_BAND_A"] / 4.4 * 32768.0, 80.0)
        self.accepted_by_the_core(self.LARGE_L, "MC_DEADTIME_BAND_A")

    def test_a_slow_motor_should_get_a_speed_scale_above_the_stall_detectors_error(self) -> None:
        t = derive.derive(desc_from(self.SLOW))
        self.assertGreater(t["MOTOR_SPEED_FULLSCALE_RPM"], 1500.0)
        self.accepted_by_the_core(self.SLOW, "MOTOR_SPEED_FULLSCALE_RPM")

    def test_a_gain_of_few_counts_in_the_core_should_be_refused_naming_its_field(self) -> None:
        # The unit-slip rule on the integers the core holds (the probe's MC_SPD_KI): at 3
        # counts the speed loop is as good as off.
        d = desc_from(HURST_TOML)
        g = generate.build(d, "test", "motor_hurst_t.h")
        g.profile.out.facts["MC_SPD_KI"] = 3.0
        with self.assertRaises(InputError) as cm:
            generate.judge(g.tuning, g.profile)
        measured("error: %s", cm.exception)
        self.assertEqual(cm.exception.field, "motor.inertia")
        self.assertIn("3 counts", str(cm.exception))


class BadInput(unittest.TestCase):
    """Each bad description: exit code non-zero, exactly one line on stderr naming the field,
    no header written."""

    def setUp(self) -> None:
        self.dir = scratch()
        self.last_line = ""

    def tearDown(self) -> None:
        shutil.rmtree(self.dir, ignore_errors=True)

    def expect_error(self, toml_text: str, field: str, fragment: str = "") -> None:
        p = os.path.join(self.dir, "m.toml")
        Path(p).write_text(toml_text, encoding="utf-8")
        out = os.path.join(self.dir, "motor_out.h")
        r = run_tune("-o", out, p)
        lines = r.stderr.strip().splitlines()
        self.assertNotEqual(r.returncode, 0)
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn(f": {field}: ", lines[0])
        self.assertIn(fragment, lines[0])
        self.assertFalse(os.path.exists(out))
        self.assertEqual([f for f in os.listdir(self.dir) if f.endswith(".h")], [], "no temp file left")
        print("measured: error line: " + lines[0])
        self.last_line = lines[0]

    def test_missing_field(self) -> None:
        self.expect_error(HURST_TOML.replace('rated_speed = "2700 rpm"\n', ""), "motor.rated_speed", "missing")

    def test_missing_section(self) -> None:
        self.expect_error('name = "x"\nboard = "mclv"\n', "motor.pole_pairs", "missing")

    def test_negative_resistance(self) -> None:
        self.expect_error(HURST_TOML.replace('"5.34 ohm"', '"-5.34 ohm"'), "motor.resistance", "> 0")

    def test_unit_typo(self) -> None:
        self.expect_error(HURST_TOML.replace('"5.34 ohm"', '"5.34 ohn"'), "motor.resistance", "unknown unit 'ohn'")

    def test_unit_of_the_wrong_quantity(self) -> None:
        self.expect_error(HURST_TOML.replace('"3.84 mH"', '"3.84 ohm"'), "motor.inductance", "unknown unit")

    def test_number_without_a_unit(self) -> None:
        self.expect_error(HURST_TOML.replace('"3.84 mH"', "3.84"), "motor.inductance", "needs a unit")

    def test_field_name_typo(self) -> None:
        self.expect_error(HURST_TOML.replace("resistance =", "resistence ="), "motor.resistence",
                          "did you mean resistance")

    def test_unknown_kind(self) -> None:
        self.expect_error(HURST_TOML.replace('resistance_kind = "line-to-line"', 'resistance_kind = "diagonal"'),
                          "motor.resistance_kind")

    def test_unknown_board(self) -> None:
        self.expect_error(HURST_TOML.replace('board = "mclv"', 'board = "mcxx"'), "board", "no boards/board_mcxx.h")

    def test_impossible_speed(self) -> None:
        self.expect_error(HURST_TOML.replace('"5300 rpm"', '"9000 rpm"'), "application.max_speed",
                          "even with field weakening")

    def test_a_rotor_the_ramp_cannot_accelerate_should_be_refused_naming_the_inertia(self) -> None:
        # hs2p under a 1e-3 kg m^2 flywheel at 40 kHz: its 11300 rpm ramp end in the 10 s the
        # forced angle allows needs 118 mN m, more than half of what its 1.5 A give
        heavy = (tool_only(read(EXAMPLES / "hispeed.toml"), 'pwm_frequency = "40 kHz"')
                 .replace('"2.0e-5 kg m^2"', '"1e-3 kg m^2"'))
        self.expect_error(heavy, "motor.inertia", "more than half")

    def test_inductance_too_small_for_the_pwm(self) -> None:
        self.expect_error(HURST_TOML.replace('"3.84 mH"', '"3.84 uH"'), "motor.inductance")

    def test_a_pwm_frequency_that_does_not_divide_the_clock_should_name_the_cores_check(self) -> None:
        self.expect_error(HURST_TOML.replace('"20 kHz"', '"7 kHz"'), "pwm_frequency",
                          "PWM_FREQUENCY_HZ (with BOARD_FCY_HZ): BOARD_FCY_HZ / PWM_FREQUENCY_HZ must be an integer")

    def test_not_toml(self) -> None:
        self.expect_error("name = \n", "file", "not valid TOML")
        line = self.last_line
        self.assertEqual(line.count("m.toml"), 1, line)  # the file named once, not twice

    def test_an_empty_key_should_be_named_as_one(self) -> None:
        self.expect_error('"" = 1\n' + HURST_TOML, '""', "empty key")
        self.expect_error(HURST_TOML.replace("[motor]\n", '[motor]\n"" = 1\n'), 'motor.""', "empty key")

    def test_no_tuning_without_a_name_is_refused(self) -> None:
        # it would replace firmware/motors/motor_hurst.h, the profile with the [tuning]
        r = run_tune("--no-tuning", str(EXAMPLES / "hurst.toml"))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("tune: ", r.stderr)
        self.assertIn("--no-tuning: give --name or -o", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)


TUNED = HURST_TOML + """
[tuning]
# the reason
MOTOR_SPEED_NOMINAL_RPM = 2500
# a table (the hand-tuned profile's, which the core takes with that nominal speed)
MOTOR_FW_ID_TABLE_A = [0, -0.399, -0.71, -1.004, -1.28, -1.541, -1.79, -2.029,
                       -2.263, -2.501, -2.769, -2.984, -2.984, -2.984, -2.984, -2.985]
"""


class Tuning_(unittest.TestCase):
    """[tuning]: the hand-tuned overrides, written as given with their reason, judged by the
    core through the probe, every problem one line naming tuning.<macro>."""

    def setUp(self) -> None:
        self.dir = scratch()

    def tearDown(self) -> None:
        shutil.rmtree(self.dir, ignore_errors=True)

    def expect(self, text: str, field: str, fragment: str, code: int = 2) -> None:
        p = os.path.join(self.dir, "m.toml")
        Path(p).write_text(text, encoding="utf-8")
        out = os.path.join(self.dir, "o.h")
        r = run_tune("--no-compile", "-o", out, p)
        self.assertEqual(r.returncode, code, r.stderr)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn(f": {field}: ", lines[0])
        self.assertIn(fragment, lines[0])
        self.assertFalse(os.path.exists(out))
        measured("tuning: %s", lines[0])

    def test_overrides_should_be_written_as_given_with_their_reason(self) -> None:
        p = os.path.join(self.dir, "m.toml")
        Path(p).write_text(TUNED, encoding="utf-8")
        out = os.path.join(self.dir, "o.h")
        r = run_tune("--no-compile", "-o", out, p)
        self.assertEqual(r.returncode, 0, r.stderr)
        h = read(out)
        self.assertIn("#define MOTOR_SPEED_NOMINAL_RPM 2500.0\n", h)
        self.assertIn("HAND-TUNED (the description's [tuning]): the reason (tools/tune alone: 2560.0)", h)
        self.assertIn("X(0.0) X(-0.399) X(-0.71) X(-1.004)", h)
        r = run_tune("--no-tuning", "--no-compile", "-o", out, p)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("#define MOTOR_SPEED_NOMINAL_RPM 2560.0\n", read(out))

    def test_bad_overrides_should_be_one_line_naming_the_macro(self) -> None:
        self.expect(HURST_TOML + "[tuning]\n# r\nMOTOR_SPEED_NOMINAL = 1.0\n", "tuning.MOTOR_SPEED_NOMINAL",
                    "did you mean MOTOR_SPEED_NOMINAL_RPM")
        self.expect(HURST_TOML + "[tuning]\n# r\nMOTOR_RS_OHM = 1.0\n", "tuning.MOTOR_RS_OHM",
                    "one home, motor.resistance")
        self.expect(HURST_TOML + "[tuning]\nMOTOR_CURRENT_MAX_A = 1.0\n", "tuning.MOTOR_CURRENT_MAX_A", "say why")
        self.expect(HURST_TOML + '[tuning]\n# r\nMOTOR_CURRENT_MAX_A = "1 A"\n', "tuning.MOTOR_CURRENT_MAX_A",
                    "expected a number")
        self.expect(HURST_TOML + "[tuning]\n# r\nMOTOR_CURRENT_MAX_A = inf\n", "tuning.MOTOR_CURRENT_MAX_A",
                    "not a finite number")
        self.expect(HURST_TOML + "[tuning]\n# r\nMOTOR_FW_ID_TABLE_A = [0.0]\n", "tuning.MOTOR_FW_ID_TABLE_A",
                    "16 numbers")
        # judged by the core's own check, through the probe
        self.expect(HURST_TOML + "[tuning]\n# r\nMOTOR_OVERCURRENT_A = 40.0\n", "tuning.MOTOR_OVERCURRENT_A",
                    "the core rejects it", code=1)


class TheProbe(unittest.TestCase):
    """tools/tune reads the core's numbers by compiling probe/probe_values.c against the real
    headers: what it reads is what the compiler computes, C's conditionals decide what a
    profile defines, and a profile that is not data is refused before it is compiled."""

    def setUp(self) -> None:
        self.dir = scratch()
        self.base = read(own_profile("hurst075"))

    def tearDown(self) -> None:
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_the_boards_values_should_be_what_the_headers_give(self) -> None:
        b = probe.board("mclv")
        # the MCLV at 20 kHz: 2000 duty counts, 80 dead-time counts (2 us at 40 MIPS), and
        # the shunt window 2 (999 + 80 - 80 - 120) = 1758 counts (mc_derived.h)
        self.assertEqual((b.name, b.fpwm, b.duty_max, b.dt_counts, b.duty_sample_max, b.loop_hz),
                         ("MCLV", 20000, 2000, 80, 1758, 1000))
        self.assertEqual(b.v_fs, 24.0 / math.sqrt(3.0))
        self.assertEqual(probe.board("mchv").name, "MCHV")
        measured("board probe: %s %d Hz, duty max %d, dead time %d counts, shunt window %d counts",
                 b.name, b.fpwm, b.duty_max, b.dt_counts, b.duty_sample_max)

    def test_userparms_defaults_should_be_computed_by_the_compiler(self) -> None:
        # UserParms.h: MC_DEADTIME_BAND_A = Vbus / (12 L fpwm), MC_ESTIMATOR_MIN_RPM = 0.8 x ramp
        # end: the Hurst075 on the MCLV, 24 V, 1.92 mH, 20 kHz, 600 rpm
        prof = core_of(own_profile("hurst075"), "mclv")
        self.assertAlmostEqual(prof.out.fact("MC_DEADTIME_BAND_A"), 24.0 / (12.0 * 1.92e-3 * 20000.0), places=12)
        self.assertEqual(prof.out.fact("MC_ESTIMATOR_MIN_RPM"), 0.8 * 600.0)

    def test_conditionals_should_decide_what_a_profile_defines(self) -> None:
        # C decides: #if 0, #ifdef, #undef and a #define inside a comment as the build reads them
        extra = ("#if 0\n#define MOTOR_RS_OHM_X 1\n#else\n#define MOTOR_RS_OHM_X 2\n#endif\n"
                 "#ifdef MOTOR_RS_OHM_X\n#define MOTOR_B_X 3\n#endif\n#ifndef MOTOR_RS_OHM_X\n#define MOTOR_C_X 4\n"
                 "#endif\n#define MOTOR_E_X 7\n#undef MOTOR_E_X\n#define MOTOR_E_X 8\n/* #define MOTOR_F_X 9 */\n"
                 '#define MOTOR_G_X "a /* b"\n')
        text = self.base.replace("#endif /* MOTOR_HURST075_H */", extra + "#endif /* MOTOR_HURST075_H */")
        m = probe.profile(text, "mclv", "x.h").macros.macros
        got = {k: v for k, v in m.items() if k.endswith("_X")}
        self.assertEqual(got, {"MOTOR_RS_OHM_X": "2", "MOTOR_B_X": "3", "MOTOR_E_X": "8", "MOTOR_G_X": '"a /* b"'})

    def test_a_profile_that_is_not_data_should_be_refused_before_it_is_compiled(self) -> None:
        cases = [("code", "static int x;\n", "C code"), ("a pragma", "#pragma weak puts = system\n", "#pragma"),
                 ("an include", '#include "UserParms.h"\n', "#include"),
                 ("a lower-case macro", "#define printf system\n", "upper-case"),
                 ("a brace in a value", "#define MOTOR_X_ 1 }\n", "'}'"),
                 ("a semicolon in a value", "#define MOTOR_X_ 1;\n", "';'"),
                 ("_Pragma in a value", '#define MOTOR_X_ _Pragma("weak puts = system") 1\n', "_Pragma"),
                 ("a renamed file", '#line 1 "mc_derived.h"\n', "#line"),
                 # a value a program would run: the simulator read MOTOR_INERTIA_KGM2 and deleted a file
                 ("a call", '#define MOTOR_X_ (remove("victim") * 0 + 7.5e-06)\n', "remove(...) is a call"),
                 ("a call with a string", '#define MOTOR_X_ (name("string"))\n', "name(...) is a call"),
                 ("an upper-case call", "#define MOTOR_X_ (SYSTEM(1) * 0 + 1.0)\n", "SYSTEM(...) is a call"),
                 ("a lower-case name", "#define MOTOR_X_ (x + 1.0)\n", "x is not a macro"),
                 ("a string in arithmetic", '#define MOTOR_X_ ("a" + 1)\n', "a string is a value on its own"),
                 # carried out by the preprocessor, absent from its output
                 ("#pragma GCC poison", "#pragma GCC poison remove\n", "#pragma"),
                 ("a pragma behind a comment", "# /* x */ pragma weak puts = system\n", "#pragma"),
                 # the board's facts: the HAL reads them without the profile
                 ("an #undef of a board fact", "#undef BOARD_I_SIGN\n", "#undef BOARD_I_SIGN"),
                 ("a redefined dead time", "#undef PWM_DEADTIME_NS\n#define PWM_DEADTIME_NS 200L\n",
                  "#undef PWM_DEADTIME_NS"),
                 ("a board fact", "#define BOARD_EXTRA_FACT 1\n", "a fact of the board")]
        for label, insert, fragment in cases:
            with self.subTest(label):
                text = self.base.replace("#endif /* MOTOR_HURST075_H */", insert + "#endif /* MOTOR_HURST075_H */")
                with self.assertRaises(InputError) as cm:
                    probe.profile(text, "mclv", "p.h")
                measured("probe refuses %s: %s", label, cm.exception)
                self.assertIn(fragment, str(cm.exception))
                self.assertTrue(str(cm.exception).startswith("p.h:"), str(cm.exception))

    def test_check_should_list_a_protection_the_profile_moves(self) -> None:
        text = self.base.replace("#endif /* MOTOR_HURST075_H */",
                                 "#define MC_SENSOR_CHECK 0\n#endif /* MOTOR_HURST075_H */")
        p = os.path.join(scratch(), "motor_prot.h")
        Path(p).write_text(text, encoding="utf-8")
        r = run_tune("--check", p, "--board", "mclv")
        self.assertEqual(r.returncode, 0, r.stderr)
        line = next((ln for ln in r.stdout.splitlines() if ln.startswith("PROTECTION")), "")
        self.assertIn("MC_SENSOR_CHECK 0", line)
        self.assertIn("current-sensor check", line)
        measured("--check lists: %s", line)

    def test_check_should_warn_of_values_a_slip_makes_likely(self) -> None:
        from tune.motortune import cli
        prof = probe.profile(self.base, "mclv", "p.h")
        facts = {k: prof.out.fact(k) for k in ("MOTOR_KE_VPK_LL_PER_KRPM", "MC_VOLTAGE_LIMIT_FRACTION",
                                               "MC_VOLTAGE_FULLSCALE_V", "MOTOR_SPEED_NOMINAL_RPM",
                                               "PWM_DEADTIME_NS", "PWM_FREQUENCY_HZ", "BOARD_VBUS_NOMINAL_V",
                                               "MOTOR_SPEED_MIN_RPM", "MOTOR_RAMP_TIME_S", "MC_VBUS_OVERVOLTAGE_V",
                                               "PWM_ADC_TRIGGER_TCY", "MC_DT_COUNTS")}
        facts["MOTOR_SPEED_MIN_RPM"] = 1000.0  # above the tool's 3 x rule: no warning of its own
        self.assertEqual(cli.unusual(facts.__getitem__), [])
        slips = [("MOTOR_KE_VPK_LL_PER_KRPM", facts["MOTOR_KE_VPK_LL_PER_KRPM"] / math.sqrt(6.0), "rms"),
                 ("MOTOR_SPEED_MIN_RPM", 300.0, "dead time's voltage error"),
                 ("MOTOR_RAMP_TIME_S", 0.02, "little"),
                 ("MC_VBUS_OVERVOLTAGE_V", 40.0, "regenerating"),
                 ("PWM_ADC_TRIGGER_TCY", 0.0, "less than a dead time")]
        for name, value, fragment in slips:
            with self.subTest(name):
                f = dict(facts, **{name: value})
                lines = [ln for ln in cli.unusual(f.__getitem__) if name in ln]
                self.assertEqual(len(lines), 1, lines)
                self.assertIn(fragment, lines[0])
                measured("--check warns: %s", lines[0])

    def test_a_profile_for_another_pwm_frequency_should_be_read_at_that_frequency(self) -> None:
        # emit.py's guard (written when the description names a pwm_frequency) names the
        # frequency the profile was derived for; --check reads it back
        guard = ("#if defined(PWM_FREQUENCY_HZ) && PWM_FREQUENCY_HZ != 10000L\n"
                 '#error "PWM_FREQUENCY_HZ: this profile was derived for 10000 Hz '
                 '(build with -DPWM_FREQUENCY_HZ=10000L)"\n#endif\n\n')
        text = self.base.replace("/* ---- electrical data", guard + "/* ---- electrical data", 1)
        self.assertNotEqual(text, self.base)
        prof = probe.profile(text, "mclv", "p.h")
        self.assertEqual(prof.build.pwm_hz, 10000)
        self.assertEqual(prof.out.fact("PWM_FREQUENCY_HZ"), 10000.0)


class UnitsAndKinds(unittest.TestCase):
    def test_equivalent_spellings_should_give_the_same_values(self) -> None:
        a = desc_from(HURST_TOML)
        b = desc_from(HURST_TOML.replace('"5.34 ohm"', '"5340 mohm"').replace('"3.84 mH"', '"3840 uH"')
                      .replace('resistance = "5340 mohm"', 'resistance = "5340 mOhm"'))
        c = desc_from(HURST_TOML.replace('resistance = "5.34 ohm"', "resistance_ohm = 5.34")
                      .replace('"5.34 ohm"', '"5.34 ohms"'))
        for x in (b, c):
            self.assertAlmostEqual(x.r_ph, a.r_ph, places=12)
            self.assertAlmostEqual(x.l_ph, a.l_ph, places=15)

    def test_si_prefixes_should_be_case_sensitive_and_the_ohm_signs_read(self) -> None:
        from tune.motortune import units
        for text, want in (("5.34 mOhm", 5.34e-3), ("5.34 m\u2126", 5.34e-3), ("5.34 m\u03a9", 5.34e-3),
                           ("5.34 \u2126", 5.34), ("5.34 \u03a9", 5.34), ("5.34 OHM", 5.34),
                           ("5.34 milliohm", 5.34e-3)):
            with self.subTest(text):
                self.assertAlmostEqual(units.parse("motor.resistance", text, "resistance"), want, places=15)
        self.assertEqual(units.parse("pwm_frequency", "20 KHz", "frequency"), 20e3)  # K is no other prefix
        self.assertEqual(units.parse("motor.rated_speed", "2700 RPM", "speed"), 2700.0)
        self.assertAlmostEqual(units.parse("motor.inductance", "3.84 \u00b5H", "inductance"), 3.84e-6, places=18)
        for text in ("5.34 MOhm", "5.34 M\u2126"):  # mega, never milli
            with self.subTest(text), self.assertRaises(InputError) as cm:
                units.parse("motor.resistance", text, "resistance")
            self.assertIn("case-sensitive", str(cm.exception))
        with self.assertRaises(InputError):
            units.parse("application.start_load", "5 MN m", "torque")

    def test_a_bare_number_should_get_a_hint_in_the_unit_its_key_needs(self) -> None:
        from tune.motortune import units
        with self.assertRaises(InputError) as cm:
            units.parse("pwm_frequency", 20000, "frequency")
        msg = str(cm.exception)
        measured("hint: %s", msg)
        self.assertIn('"20 kHz"', msg)
        self.assertNotIn("20000 kHz", msg)
        self.assertIn("pwm_frequency_hz", msg)

    def test_a_unit_in_the_key_and_in_the_string_should_agree(self) -> None:
        from tune.motortune import units
        self.assertEqual(units.parse("motor.resistance_ohm", "5.34 ohm", "resistance"), 5.34)
        self.assertAlmostEqual(units.parse("motor.resistance_mohm", "5.34", "resistance"), 5.34e-3, places=15)
        with self.assertRaises(InputError) as cm:
            units.parse("motor.resistance_mohm", "5.34 ohm", "resistance")
        self.assertIn("give the unit once", str(cm.exception))
        b = desc_from(HURST_TOML.replace('resistance = "5.34 ohm"', 'resistance_ohm = "5.34 ohm"'))
        self.assertAlmostEqual(b.r_ph, 2.67, places=12)

    def test_per_phase_and_rms_kinds_should_convert(self) -> None:
        a = desc_from(HURST_TOML)
        b = desc_from(HURST_TOML.replace('"5.34 ohm"', '"2.67 ohm"').replace(
            'resistance_kind = "line-to-line"', 'resistance_kind = "per-phase"').replace(
            '"7.3 V/krpm"', f'"{7.3 / math.sqrt(2):.9f} V/krpm"').replace(
            'back_emf_kind = "peak line-to-line"', 'back_emf_kind = "rms line-to-line"'))
        self.assertAlmostEqual(b.r_ph, a.r_ph, places=12)
        self.assertAlmostEqual(b.ke_ll, a.ke_ll, places=6)
        c = desc_from(HURST_TOML.replace('"7.3 V/krpm"', '"7.3 mV/rpm"'))
        self.assertAlmostEqual(c.ke_ll, 7.3, places=12)


class GeneratedHeaders(unittest.TestCase):
    dir: str
    out: dict[str, tuple[str, str]]
    committed: dict[str, str]

    @classmethod
    def setUpClass(cls) -> None:
        cls.dir = scratch()
        cls.out = {}
        cls.committed = {}
        for ex, (name, board) in EXAMPLE_PROFILES.items():
            h = os.path.join(cls.dir, f"motor_{name}.h")
            r = run_tune("--no-tuning", "--name", name, "-o", h, str(EXAMPLES / f"{ex}.toml"))
            assert r.returncode == 0, r.stderr
            cls.out[ex] = (h, board)
            c = os.path.join(cls.dir, f"committed_{ex}.h")
            r = run_tune("--no-compile", "-o", c, str(EXAMPLES / f"{ex}.toml"))
            assert r.returncode == 0, r.stderr
            cls.committed[ex] = c

    @classmethod
    def tearDownClass(cls) -> None:
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_headers_should_define_every_macro_of_the_hand_tuned_profile(self) -> None:
        hand = core_of(MOTORS / "motor_hurst.h", "mclv").macros.macros
        want = {n for n in hand if not n.endswith("_H")}
        for ex, (h, board) in self.out.items():
            with self.subTest(ex):
                missing = want - set(core_of(h, board).macros.macros)
                self.assertEqual(missing, set(), f"{ex} lacks {sorted(missing)}")

    def test_check_should_round_trip_what_the_generator_wrote(self) -> None:
        for ex, (h, board) in self.out.items():
            with self.subTest(ex):
                t = derive.derive(describe.load(str(EXAMPLES / f"{ex}.toml")))
                r = run_tune("--check", h)
                self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
                self.assertIn("every check of mc_derived.h / smc.h / the core passes", r.stdout)
                rows = rows_of(core_of(h, board))
                worst = 0.0
                for v in t.values:
                    row = rows.get(v.macro)
                    if row is None or row.q is None or row.decoded is None:
                        continue
                    self.assertAlmostEqual(row.eng, v.number, delta=abs(v.number) * 5e-4 + 1e-12, msg=v.macro)
                    if row.unit in ("A", "rpm", "V", "V/A", "A/rpm", "A/(rpm s)", "V/(A s)") and v.number:
                        rel = abs(row.decoded - v.number) / abs(v.number)
                        worst = max(worst, rel)
                        self.assertLess(rel, 5e-3, v.macro)  # Q15 resolution at these magnitudes
                fw = fw_rows(core_of(h, board))
                self.assertEqual(len(fw), 16)
                for a, row in zip(t.fw_table, fw, strict=True):
                    self.assertAlmostEqual(row.eng, a, places=9)
                    assert row.decoded is not None
                    self.assertAlmostEqual(row.decoded, a, delta=t.i_fs / 32768.0)
                measured("%s: --check decodes every generated value within %.2e relative", ex, worst)

    def test_headers_should_compile_with_the_core(self) -> None:
        cc = probe.find_cc()
        for ex, (h, board) in self.out.items():
            with self.subTest(ex):
                cmd = [*cc, "-std=c99", "-fsyntax-only", "-Wall", "-Wextra", "-Werror", "-Wconversion",
                       "-Wsign-conversion", "-Wshadow", f"-I{REPO}/firmware", f"-I{REPO}/foc",
                       f"-I{REPO}/smc_estimator", f"-DMC_BOARD_{board.upper()}",
                       f'-DMC_MOTOR_HEADER="{h}"', *sorted(glob.glob(os.path.join(REPO, "firmware", "mc*.c")))]
                r = subprocess.run(cmd, capture_output=True, text=True)
                self.assertEqual(r.returncode, 0, r.stderr)

    def test_check_should_print_the_integers_the_c_compiler_computes(self) -> None:
        # The Q15 integers --check prints, against the same constants compiled by this test
        # from firmware/mc_derived.h and smc.h's SMC_PARAMS_INIT, independently of the probe.
        cc = probe.find_cc()
        prog = r"""
#include <stdio.h>
#include "mc_derived.h"
static const smc_params_t p = MC_SMC_PARAMS_INIT;
static const q15_t fw[16] = MC_FW_TABLE_Q15;
int main(void)
{
    int k;
    printf("f %d\ng %d\nkslide %d\nmax_err %d\nkz %d\n", p.f, p.g, p.kslide, p.max_err, p.kz);
    printf("cur_kp %d\ncur_ki %d\nspd_kp %d\nspd_ki %d\n", MC_CUR_KP, MC_CUR_KI, MC_SPD_KP, MC_SPD_KI);
    printf("iq_max %d\ntrip %d\nlock %d\nlock_periods %u\nramp_inc %lu\n", MC_IQ_MAX_Q15,
           MC_OVERCURRENT_Q15, MC_LOCK_CURRENT_Q15, (unsigned)MC_LOCK_PERIODS,
           (unsigned long)MC_RAMP_STEP_INC);
    for (k = 0; k < 16; k++) printf("fw%d %d\n", k, fw[k]);
    return 0;
}
"""
        want = {"f": "smc F = exp(-Ts R/L)", "g": "smc G = (1-F)/R * 2V_FS/I_FS", "kslide": "MOTOR_SMC_GAIN_V",
                "max_err": "MOTOR_SMC_LINEAR_BAND_A", "kz": "smc Kz = Kslide / MaxSMCError",
                "cur_kp": "MOTOR_CURRENT_KP_V_PER_A", "cur_ki": "MOTOR_CURRENT_KI_V_PER_AS",
                "spd_kp": "MOTOR_SPEED_KP_A_PER_RPM", "spd_ki": "MOTOR_SPEED_KI_A_PER_RPM_S",
                "iq_max": "MOTOR_CURRENT_MAX_A", "trip": "MC_OVERCURRENT_A", "lock": "MOTOR_LOCK_CURRENT_A",
                "lock_periods": "MOTOR_LOCK_TIME_S", "ramp_inc": "ramp acceleration"}
        for ex, (h, board) in self.out.items():
            with self.subTest(ex):
                src = os.path.join(self.dir, f"consts_{ex}.c")
                exe = os.path.join(self.dir, f"consts_{ex}")
                Path(src).write_text(prog, encoding="utf-8")
                r = subprocess.run([*cc, "-std=c99", "-w", f"-I{REPO}/firmware", f"-I{REPO}/foc",
                                    f"-I{REPO}/smc_estimator", f"-DMC_BOARD_{board.upper()}",
                                    f'-DMC_MOTOR_HEADER="{h}"', src, "-o", exe], capture_output=True, text=True)
                self.assertEqual(r.returncode, 0, r.stderr)
                out = subprocess.run([exe], capture_output=True, text=True).stdout
                got = dict(line.split() for line in out.splitlines())
                prof = core_of(h, board)
                rows = rows_of(prof)
                n = 0
                for key, name in want.items():
                    self.assertEqual(int(got[key]), rows[name].q, f"{key} ({name})")
                    n += 1
                for k, row in enumerate(fw_rows(prof)):
                    self.assertEqual(int(got[f"fw{k}"]), row.q)
                    n += 1
                measured("%s: %d integers of --check equal the C compiler's", ex, n)

    def test_committed_profiles_should_be_what_the_tool_writes(self) -> None:
        # one committed profile per example, with its [tuning]; the tool's own (without) is
        # built, never committed
        for ex, h in self.committed.items():
            committed = MOTORS / f"motor_{ex}.h"
            with self.subTest(ex):
                self.assertTrue(committed.exists(), committed)
                self.assertEqual(read(h), read(committed), f"firmware/motors/motor_{ex}.h is stale: run "
                                 f"tools/tune/tune tools/tune/examples/{ex}.toml")
        for ex, (name, _) in EXAMPLE_PROFILES.items():
            if name != ex:
                self.assertFalse((MOTORS / f"motor_{name}.h").exists(), f"motor_{name}.h is built, not committed")

    def test_the_build_trees_own_profiles_should_be_what_the_tool_writes(self) -> None:
        built = os.environ.get("TUNE_PROFILES")
        if not built:
            self.skipTest("TUNE_PROFILES not set: run through CTest")
        for ex, (h, _) in self.out.items():
            name = EXAMPLE_PROFILES[ex][0]
            p = Path(built) / f"motor_{name}.h"
            if name == ex:
                continue
            with self.subTest(ex):
                self.assertEqual(read(h), read(p), f"{p} is stale")

    def test_check_should_decode_the_hand_tuned_profiles(self) -> None:
        for name, board in (("hurst", "mclv"), ("hurst300", "mclv"), ("hispeed", "mchv")):
            with self.subTest(name):
                r = run_tune("--check", str(MOTORS / f"motor_{name}.h"), "--board", board)
                self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
                self.assertIn("MOTOR_SMC_GAIN_V", r.stdout)

    def test_check_should_report_a_value_the_core_would_reject(self) -> None:
        h, _ = self.out["hurst"]
        bad = os.path.join(self.dir, "motor_bad.h")
        Path(bad).write_text(read(h).replace("#define MOTOR_CURRENT_MAX_A 1.64", "#define MOTOR_CURRENT_MAX_A 4.0"),
                             encoding="utf-8")
        r = run_tune("--check", bad)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("CHECK FAILED  MC_OVERCURRENT_A", r.stdout)
        self.assertIn("CHECK FAILED  MOTOR_OVERCURRENT_A (with MOTOR_CURRENT_MAX_A): must be in "
                      "(MOTOR_CURRENT_MAX_A, BOARD_I_FULLSCALE_A) (firmware/mc_derived.h:", r.stdout)

    def test_check_should_give_the_cores_own_refusal_with_or_without_compiling_mc_c(self) -> None:
        # A value only the core judges (the loop bandwidth documents the gains below it):
        # --check answers with the core's check, its parameter and its reason.
        h, _ = self.out["hurst"]
        bad = os.path.join(self.dir, "motor_bw.h")
        text = read(h)
        self.assertIn("#define MOTOR_CURRENT_LOOP_BW_RAD_S 3000.0", text)
        Path(bad).write_text(text.replace("#define MOTOR_CURRENT_LOOP_BW_RAD_S 3000.0",
                                          "#define MOTOR_CURRENT_LOOP_BW_RAD_S 30000.0"), encoding="utf-8")
        for opts in ((), ("--no-compile",)):
            with self.subTest(opts):
                r = run_tune("--check", bad, *opts)
                self.assertEqual(r.returncode, 1, r.stderr)
                lines = r.stderr.splitlines()
                self.assertEqual(len(lines), 1, r.stderr)
                self.assertIn("MOTOR_CURRENT_LOOP_BW_RAD_S: must be in (0, PWM_FREQUENCY_HZ) rad/s", lines[0])


if __name__ == "__main__":
    unittest.main()
