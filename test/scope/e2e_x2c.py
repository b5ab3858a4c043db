# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""End to end: tools/scope against the firmware's X2Cscope target served by `sim --pty
--realtime 0` over a real pseudo-terminal (and once over TCP).

  Services    device info (processor 0x8210), get target state, read, write, load and save
              parameter 1; services the target refuses (0x19 reboot, 0x02 set state: 0x21);
              a request with a bad checksum (0x13) and a 0x02 without its fill (0x14).
  Escaping    0x55 / 0x02 in an address (0x0802, 0x0955), in a count (85 bytes), in SIZE (a
              reply and a request of 0x55 data bytes), in written data (0x0255, 0x5502), and
              inverted checksums counted in both directions (> 0).
  Chunks      the scope buffer (its address and size from load parameter) read in 253-byte
              requests, equal to the same bytes read in other pieces.
  Whitelist   every refusal (outside, straddling, odd address, width 3, count not whole, 254
              bytes, read-only, partial, out of range, scope channel / trigger outside, 9
              channels, unknown parameter id), each followed by a read-back of every tunable
              and of the scope's state proving nothing changed.
  Trigger     a motor start (motor.state rising past 1) captured with a pre-trigger history
              (11 datasets: never where the sim's 20-period cadence lands the trigger, so the
              ring is really rotated; the dataset at index 11 is the first at or past the level,
              the one before is below it, and motor.timer runs on by one per dataset across the
              rotated ring's seam) and with delay -30 (the first dataset is 30 periods after
              the edge: motor.timer = its value at the edge + 30), and an auto trigger.
  Speed       the motor at 1000 rpm: every dataset of motor.smc.omega (rpm by the map's full
              scale) equals the simulator's --truth speed_est_rpm for the same dataset within
              0.1 %, and the capture's mean equals the mean true rotor speed (speed_true_rpm)
              within 0.1 %; the largest deviation from it is printed (measured:).
  Transports  pyserial on the same pty; sim --tcp on a free port: device info, a read, a
              capture, the command's info.
  Command     an1078-scope info / read / write (refused: exit 1 naming 0x42) / capture --csv
              --png (and not again over them) / a start captured with --then x2c.tune.run=1 /
              a trigger timeout / live --headless.

usage: e2e_x2c.py <sim executable> <repo root> <output dir>
Exit status 77 (CTest: skipped, the reason on stdout) without a pseudo-terminal or without
the venv's pyyaml, pyelftools or matplotlib.
"""

from __future__ import annotations

import csv
import functools
import importlib.util
import itertools
import os
import select
import signal
import socket
import struct
import subprocess
import sys
import termios
import time
import tty
import unittest
from collections.abc import Callable
from typing import Any

SKIP = 77
SIM = ROOT = OUT = ""

HERE = os.path.dirname(os.path.abspath(__file__))


def skip_without_tools() -> None:
    why = [f"{m} is not installed (run tools/bootstrap)" for m in ("yaml", "elftools", "matplotlib")
           if importlib.util.find_spec(m) is None]
    if not os.path.exists("/dev/ptmx"):
        why.append("no pseudo-terminals here (/dev/ptmx)")
    if why:
        print(f"SKIPPED: {'; '.join(why)}")
        sys.exit(SKIP)


if __name__ == "__main__":
    skip_without_tools()

from scope import lnet, varmap, x2c  # noqa: E402  (after the skip check: the packages may be missing)


class Sim:
    """sim --pty --realtime 0 [extra], its pty (and tcp) from the first lines it prints."""

    def __init__(self, *extra: str) -> None:
        self.proc = subprocess.Popen([SIM, "--pty", "--realtime", "0", *extra], stdout=subprocess.PIPE, text=True)
        assert self.proc.stdout is not None
        self.pty = self.tcp = ""
        for _ in range(3):
            line = self.proc.stdout.readline()
            if line.startswith("pty: "):
                self.pty = line.split()[1]
            elif line.startswith("tcp: "):
                self.tcp = "tcp://" + line.split()[1]
            if self.pty and (self.tcp or "--tcp" not in extra):
                break
        if not self.pty:
            self.stop()
            raise RuntimeError(f"sim printed no pty (exit {self.proc.poll()})")

    def stop(self) -> str:
        """Ends it (SIGTERM: the --truth file is closed) and returns the rest of its output."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            out, _ = self.proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, _ = self.proc.communicate()
        return out or ""


def connect(port: str) -> x2c.Target:
    t = x2c.Target(lnet.Link(lnet.open_transport(port), timeout=2.0))
    t.device_info()
    return t


class State:
    """What setUpModule opens for every test: the map, the simulator, the target on its pty."""

    map: varmap.VarMap
    sim: Sim
    t: x2c.Target
    size: int  # the scope buffer's bytes, as load parameter reports them
    base: int  # its address


ST = State()


def var(name: str) -> varmap.Var:
    return ST.map.get(name)


def read_var(t: x2c.Target, name: str) -> int:
    v = var(name)
    val = x2c.Channel(v.address, v.size, v.kind).decode(t.read(v.address, v.size, v.size))
    assert isinstance(val, int)
    return val


def write_var(t: x2c.Target, name: str, value: int) -> None:
    v = var(name)
    t.write(v.address, v.size, value.to_bytes(v.size, "little", signed=value < 0))


def tunables(t: x2c.Target) -> dict[str, int]:
    return {n: read_var(t, n) for n, v in ST.map.vars.items() if v.tunable}


def wait_for(what: str, cond: Callable[[], bool], timeout: float = 20.0) -> None:
    t_end = time.monotonic() + timeout
    while not cond():
        if time.monotonic() > t_end:
            raise AssertionError(f"{what}: not within {timeout:g} s")
        time.sleep(0.01)


def stop_motor(t: x2c.Target) -> None:
    write_var(t, "x2c.tune.run", 0)
    wait_for("motor stopped", lambda: read_var(t, "motor.state") == 0)


def ch(name: str) -> x2c.Channel:
    v = var(name)
    return x2c.Channel(v.address, v.size, v.kind)


def setUpModule() -> None:
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, "x2cmap.yml")
    if os.path.exists(path):
        os.remove(path)  # this test's own output of an earlier run
    rc = varmap.main([SIM, "-o", path])
    assert rc == 0, "an1078-x2cmap failed"
    ST.map = varmap.load_map(path)
    ST.sim = Sim()
    ST.t = connect(ST.sim.pty)
    st = ST.t.scope_state()
    ST.size, ST.base = st.buffer_size, st.buffer_address
    # fill the scope buffer with varied bytes: motor.timer counts every period
    ST.t.capture(x2c.ScopeConfig((ch("motor.timer"), ch("motor.state"))), timeout=5)


def tearDownModule() -> None:
    ST.t.link.close()
    out = ST.sim.stop()
    print("sim: " + " / ".join(ln.strip() for ln in out.splitlines() if ln.strip()))


class A_Services(unittest.TestCase):  # the classes run in name order
    def assertRefused(self, code: int, fn: Callable[[], Any]) -> None:
        before = self.snapshot()
        with self.assertRaises(x2c.TargetError) as cm:
            fn()
        self.assertEqual(cm.exception.code, code, str(cm.exception))
        self.assertEqual(self.snapshot(), before, "a refused request changed something")
        self.refusals += 1

    def snapshot(self) -> tuple[dict[str, int], x2c.ScopeState, int]:
        return tunables(ST.t), ST.t.scope_state(), read_var(ST.t, "motor.fault")

    def setUp(self) -> None:
        self.refusals = 0

    def test_01_device_info_and_target_state(self) -> None:
        i = ST.t.device_info()
        self.assertEqual((i.processor_id, i.monitor_version, i.max_frame), (0x8210, 5, 255))
        self.assertEqual(ST.t.target_state(), i.dsp_state)
        self.assertEqual(i.dsp_state, 0x04)  # stopped: outputs off

    def test_02_services_the_target_refuses(self) -> None:
        self.assertRefused(0x21, lambda: ST.t.call(x2c.SVC_REBOOT))
        self.assertRefused(0x21, lambda: ST.t.call(0x02, b"\x05"))  # set target state
        # a request with a bad checksum: the reply names its service with 0x13
        wire = bytearray(lnet.encode(b"\x01"))
        wire[-1] ^= 0x01
        ST.t.link.send_raw(bytes(wire))
        ev = ST.t.link.receive()
        self.assertIsInstance(ev, lnet.Frame)
        assert isinstance(ev, lnet.Frame)
        self.assertEqual(ev.data, b"\x01\x13")
        # a 0x02 without its fill: 0x14 under service 0
        ST.t.link.send_raw(bytes((0x55, 0x01, 0x01, 0x02, 0x07, 0x00)))
        ev = ST.t.link.receive()
        assert isinstance(ev, lnet.Frame), ev
        self.assertEqual(ev.data, b"\x00\x14")
        self.assertEqual(ST.t.target_state(), 0x04)  # and the next request is answered

    def test_03_every_map_variable_should_be_readable_with_its_width(self) -> None:
        for v in ST.map.vars.values():
            self.assertEqual(len(ST.t.read(v.address, v.size, v.size)), v.size, v.name)
            if v.size > 1:
                self.assertEqual(len(ST.t.read(v.address + 1, 1, 1)), 1, v.name)  # a byte inside it
        # each tunable takes its own value back
        for name, value in tunables(ST.t).items():
            if name != "x2c.tune.run":
                write_var(ST.t, name, value)
                self.assertEqual(read_var(ST.t, name), value, name)

    def test_04_reserved_bytes_in_every_field(self) -> None:
        s = ST.t.link.stats
        kept = read_var(ST.t, "x2c.tune.cur_ki")
        self.assertEqual(var("x2c.tune.cur_ki").address, 0x0802)  # 0x02 in the address
        try:
            for value in (0x0255, 0x5502):  # data bytes 55 02 and 02 55
                write_var(ST.t, "x2c.tune.cur_ki", value)
                self.assertEqual(read_var(ST.t, "x2c.tune.cur_ki"), value)
        finally:
            write_var(ST.t, "x2c.tune.cur_ki", kept)
        self.assertEqual(read_var(ST.t, "x2c.tune.cur_ki"), kept)
        buf = ST.t.read(0x0900, ST.size)
        self.assertEqual(ST.t.read_once(0x0955, 1), buf[0x55:0x56])  # 0x55 in the address
        self.assertEqual(ST.t.read_once(0x0900, 0x55), buf[:0x55])  # a count of 0x55
        self.assertEqual(ST.t.read_once(0x0955, 0x55), buf[0x55:0xAA])  # both
        self.assertEqual(ST.t.read_once(0x0900, 83), buf[:83])  # a reply of SIZE 0x55
        # a request of SIZE 0x55: an 81-byte write, longer than any request the target takes
        # (x2c.h X2C_REQUEST_MAX): refused whole, 0x15 under service 0
        self.assertRefused(0x15, lambda: ST.t.write(0x0900, 1, bytes(81)))
        # inverted checksums: reads whose request sums to 0x55 and to 0x02 ...
        sent0, recv0 = s.crc_inverted_sent, s.crc_inverted_received
        sums = {lnet.crc_raw(5, 1, bytes((0x09, 0x00, 0x09, n, 1))): n for n in range(1, 254)}
        for raw in lnet.RESERVED:
            self.assertEqual(ST.t.read_once(0x0900, sums[raw]), buf[:sums[raw]])
        # ... and reads whose reply (09 00 data) sums to one of them
        found: dict[int, tuple[int, int]] = {}
        for a in range(0, ST.size - 1):
            for n in range(1, min(253, ST.size - a) + 1):
                raw = lnet.crc_raw(n + 2, 1, b"\x09\x00" + buf[a:a + n])
                if raw in lnet.RESERVED and raw not in found:
                    found[raw] = (a, n)
            if len(found) == 2:
                break
        self.assertTrue(found, "no read of the buffer has a reserved reply sum")
        for a, n in found.values():
            before = s.crc_inverted_received
            self.assertEqual(ST.t.read_once(0x0900 + a, n), buf[a:a + n])
            self.assertEqual(s.crc_inverted_received, before + 1, f"the reply to a read of {n} at +{a}")
        self.assertGreaterEqual(s.crc_inverted_sent - sent0, 2)
        self.assertGreaterEqual(s.crc_inverted_received - recv0, 1)
        self.assertGreater(s.fills_sent, 0)
        self.assertGreater(s.fills_received, 0)
        print(f"measured: frames sent {s.frames_sent}, received {s.frames_received}; inverted checksums "
              f"sent {s.crc_inverted_sent}, received {s.crc_inverted_received}; fill bytes sent {s.fills_sent}, "
              f"received {s.fills_received}")

    def test_05_the_buffer_in_253_byte_chunks(self) -> None:
        st = ST.t.scope_state()
        self.assertEqual((st.buffer_address, st.version), (0x0900, 0x82))  # the window's, x2c.h
        self.assertEqual(st.used_length, st.buffer_size - st.buffer_size % 8)  # the last capture: 8-byte datasets
        self.assertGreater(st.used_length, 253, "a buffer this small needs no chunks")
        n0 = ST.t.link.stats.frames_sent
        whole = ST.t.read(st.buffer_address, st.used_length)
        self.assertEqual(ST.t.link.stats.frames_sent - n0, -(-st.used_length // 253))  # 253 + the rest
        pieces = b"".join(ST.t.read(st.buffer_address + k, min(100, st.used_length - k))
                          for k in range(0, st.used_length, 100))
        self.assertEqual(whole, pieces)
        self.assertGreater(len(set(whole)), 16, "the buffer holds the capture's varied bytes")

    def test_06_every_whitelist_refusal_should_change_nothing(self) -> None:
        r = ST.t.read_once
        end = ST.base + ST.size
        for addr in (0x0000, 0x07FE, 0x080E, 0x087E, end, 0x1000, 0xFFFF):  # outside every variable
            self.assertRefused(0x14, functools.partial(r, addr, 1, 1))
        self.assertRefused(0x14, lambda: r(0x0800, 4, 2))  # two tunables
        self.assertRefused(0x14, lambda: r(var("motor.ia").address, 4, 2))  # motor.ia and motor.ib
        self.assertRefused(0x14, lambda: r(end - 16, 32, 1))  # past the buffer's end
        self.assertRefused(0x14, lambda: r(0x0801, 2, 2))  # odd address, width 2
        self.assertRefused(0x14, lambda: r(0x0901, 4, 4))
        self.assertRefused(0x14, lambda: r(0x0900, 3, 3))  # width 3
        self.assertRefused(0x14, lambda: r(0x0900, 2, 0))  # width 0
        self.assertRefused(0x14, lambda: r(0x0900, 3, 2))  # count not a multiple of the width
        self.assertRefused(0x14, lambda: r(0x0900, 0, 1))  # nothing
        self.assertRefused(0x15, lambda: r(0x0900, 254, 1))  # more than a reply holds
        self.assertRefused(0x15, lambda: r(0x0900, 255, 1))
        w = ST.t.write
        for name in ("motor.fault", "motor.state", "motor.smc.omega", "motor.outputs_on",
                     "x2c.id.status", "x2c.id.rs_uohm"):  # read-only
            v = var(name)
            self.assertRefused(0x14, functools.partial(w, v.address, v.size, (1).to_bytes(v.size, "little")))
        self.assertRefused(0x14, lambda: w(0x0800, 1, b"\x10"))  # half a tunable
        self.assertRefused(0x14, lambda: w(0x0801, 1, b"\x10"))
        self.assertRefused(0x14, lambda: w(0x0801, 2, b"\x10\x20"))  # odd address
        self.assertRefused(0x14, lambda: w(0x0800, 2, b"\x10\x20\x30\x40"))  # two tunables
        self.assertRefused(0x14, lambda: w(0x0800, 3, b"\x10\x20\x30"))  # width 3
        self.assertRefused(0x14, lambda: w(0x0700, 2, b"\x10\x20"))  # outside
        self.assertRefused(0x14, lambda: w(0x0900, 2, b"\x10\x20"))  # the scope buffer
        for name, value in (("x2c.tune.cur_kp", var("x2c.tune.cur_kp").min - 1),
                            ("x2c.tune.cur_ki", var("x2c.tune.cur_ki").max + 1),
                            ("x2c.tune.run", 2), ("x2c.tune.run", -1), ("x2c.tune.identify", 2),
                            ("x2c.tune.speed_ref_rpm", var("x2c.tune.speed_ref_rpm").max + 1),
                            ("x2c.tune.speed_ref_rpm", -100)):
            self.assertRefused(0x42, functools.partial(write_var, ST.t, name, value))
        timer = ch("motor.timer")
        ok_trig = x2c.Trigger(timer.address, 4, "U", 5, delay=0)

        def save(*chans: x2c.Channel, trig: x2c.Trigger | None = None) -> Callable[[], None]:
            return lambda: ST.t.scope_save(x2c.ScopeConfig(chans, 0, trig))

        self.assertRefused(0x14, save(x2c.Channel(0x0700, 2)))  # a channel outside
        self.assertRefused(0x14, save(x2c.Channel(var("x2c.id.ls_nh").address, 4)))  # the result: no channel
        self.assertRefused(0x14, save(timer, x2c.Channel(0x0801, 2)))  # odd
        self.assertRefused(0x14, save(x2c.Channel(0x0800, 4)))  # straddling two tunables
        self.assertRefused(0x14, save(x2c.Channel(0x0800, 3)))  # width 3
        self.assertRefused(0x14, save(timer, trig=x2c.Trigger(0x0700, 2, "S", 0)))  # trigger outside
        self.assertRefused(0x14, save(timer, trig=x2c.Trigger(end, 1, "U", 0)))
        self.assertRefused(0x15, save(*([timer] * 9)))  # 9 channels: longer than the largest request
        ring = ST.size // 4
        self.assertRefused(0x42, save(timer, trig=x2c.Trigger(timer.address, 4, "U", 5, delay=ring)))  # > the ring
        self.assertRefused(0x40, lambda: ST.t.call(x2c.SVC_LOAD_PARAM, b"\x02\x00"))  # unknown parameter id
        self.assertRefused(0x40, lambda: ST.t.call(x2c.SVC_LOAD_PARAM, b"\x01\x01"))
        good = x2c.ScopeConfig((timer,), 0, ok_trig).encode()
        self.assertRefused(0x40, lambda: ST.t.scope_save_raw(good, param=2))
        bad_delay = good[:-6] + struct.pack("<i", 6) + good[-2:]  # not whole datasets
        self.assertRefused(0x14, lambda: ST.t.scope_save_raw(bad_delay))
        self.assertRefused(0x14, lambda: ST.t.scope_save_raw(bytes((3,)) + good[1:]))  # state 3
        print(f"measured: {self.refusals} refusals, each followed by an unchanged read-back")

    def test_07_trigger_positive_and_negative_delay_on_a_motor_start(self) -> None:
        state, timer = ch("motor.state"), ch("motor.timer")
        self.assertEqual(read_var(ST.t, "motor.state"), 0)

        def start() -> None:
            write_var(ST.t, "x2c.tune.run", 1)

        n = ST.size // 8
        # the sim serves requests once a millisecond, 20 periods: the trigger lands on a multiple of
        # 20 datasets (mod n); a history that is none of them makes the rotation never 0
        pre = next(p for p in range(11, n) if p not in {20 * k % n for k in range(n)})
        cfg = x2c.ScopeConfig((state, timer), 0, x2c.Trigger(state.address, 4, "U", 1, delay=pre, rising=True))
        try:
            cap = ST.t.capture(cfg, timeout=10, after_start=start)
        finally:
            stop_motor(ST.t)
        st = cap.state
        self.assertEqual(len(cap.datasets), n)
        self.assertEqual(st.trigger_delay, pre * 8)
        self.assertEqual(cap.shift, (st.trigger_position // 8 - pre) % n)
        self.assertNotEqual(cap.shift, 0)
        s, tm = cap.channel(0), cap.channel(1)
        self.assertTrue(s[pre - 1] < 1 <= s[pre], f"no crossing at {pre}: {s[pre - 2:pre + 2]}")
        self.assertEqual(s[:pre], [0] * pre)
        for i in range(1, n):  # one period a dataset, in order across the ring's seam
            if s[i] == s[i - 1]:
                self.assertEqual(tm[i], tm[i - 1] + 1, f"dataset {i}")
        t_edge = tm[pre]
        print(f"measured: trigger at byte {st.trigger_position} of the ring, rotated by {cap.shift} datasets; "
              f"motor.state {s[pre - 1]} -> {s[pre]} at dataset {pre}, motor.timer there {t_edge}")

        wait = 30
        cfg = x2c.ScopeConfig((state, timer), 0, x2c.Trigger(state.address, 4, "U", 1, delay=-wait))
        try:
            cap = ST.t.capture(cfg, timeout=10, after_start=start)
        finally:
            stop_motor(ST.t)
        st = cap.state
        self.assertEqual((st.trigger_delay, st.trigger_position, cap.shift), (-wait * 8, 0, 0))
        s, tm = cap.channel(0), cap.channel(1)
        self.assertEqual(s, [s[pre]] * n, "the whole capture in the state the edge entered")
        self.assertEqual(tm, [t_edge + wait + i for i in range(n)])
        print(f"measured: delay -{wait}: first dataset at motor.timer {tm[0]} = the edge's {t_edge} + {wait}")

        cfg = x2c.ScopeConfig((timer,), 1, x2c.Trigger(0, 2, "U", 0, delay=10, auto=True))
        cap = ST.t.capture(cfg, timeout=10)
        tm = cap.channel(0)
        self.assertEqual(len(tm), ST.size // 4)
        self.assertEqual([b - a for a, b in itertools.pairwise(tm)], [2] * (len(tm) - 1))  # prescaler 1

    def test_08_a_pyserial_port_should_work_too(self) -> None:
        if importlib.util.find_spec("serial") is None:
            self.skipTest("pyserial is not installed")
        t = x2c.Target(lnet.Link(lnet.open_transport(ST.sim.pty, kind="serial"), timeout=2.0))
        try:
            self.assertEqual(t.device_info().processor_id, 0x8210)
            self.assertEqual(read_var(t, "x2c.tune.cur_kp"), read_var(ST.t, "x2c.tune.cur_kp"))
        finally:
            t.link.close()


def scope_cli(*argv: str) -> tuple[int, str, str]:
    p = subprocess.run([sys.executable, "-m", "scope", "--port", ST.sim.pty, "--map", os.path.join(OUT, "x2cmap.yml"),
                        *argv], capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout, p.stderr


class B_Command(unittest.TestCase):
    def assertOneLine(self, rc: int, err: str, code: int, *want: str) -> None:
        self.assertEqual(rc, code, err)
        self.assertEqual(len(err.splitlines()), 1, err)
        self.assertNotIn("Traceback", err)
        for w in want:
            self.assertIn(w, err)

    def test_info_read_write(self) -> None:
        rc, out, err = scope_cli("info")
        self.assertEqual(rc, 0, err)
        self.assertIn("processor 0x8210", out)
        rc, out, err = scope_cli("read", "motor.state", "x2c.tune.cur_kp", "motor.vbus")
        self.assertEqual(rc, 0, err)
        self.assertIn("(STOPPED)", out)
        self.assertRegex(out, r"motor\.vbus +raw \d+ += [\d.]+ V")
        kept = read_var(ST.t, "x2c.tune.spd_kp")
        rc, out, err = scope_cli("write", "x2c.tune.spd_kp", str(kept + 1))
        self.assertEqual(rc, 0, err)
        self.assertIn(f"wrote {kept + 1}, reads back {kept + 1}", out)
        write_var(ST.t, "x2c.tune.spd_kp", kept)
        rc, out, err = scope_cli("write", "x2c.tune.cur_kp", "1")
        self.assertOneLine(rc, err, 1, "error 0x42 (limit", f"it reads {read_var(ST.t, 'x2c.tune.cur_kp')}")
        rc, out, err = scope_cli("write", "motor.state", "1")
        self.assertOneLine(rc, err, 1, "error 0x14 (format")
        rc, out, err = scope_cli("read", "motor.nothing")
        self.assertOneLine(rc, err, 2, "unknown variable")

    def test_capture_to_csv_and_png_then_not_over_them(self) -> None:
        csv_p, png_p = os.path.join(OUT, "capture.csv"), os.path.join(OUT, "capture.png")
        for p in (csv_p, png_p):
            if os.path.exists(p):
                os.remove(p)
        rc, out, err = scope_cli("capture", "motor.timer", "motor.vbus", "--prescaler", "3", "--csv", csv_p,
                                 "--png", png_p)
        self.assertEqual(rc, 0, err)
        n = ST.size // 6
        self.assertIn(f"captured {n} datasets of 6 bytes, one every 200 µs", out)
        self.assertIn("capture:", err)  # the progress line
        with open(csv_p, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        self.assertEqual(rows[0], ["t_s", "motor.timer", "motor.vbus_V"])
        self.assertEqual(len(rows), n + 1)
        self.assertAlmostEqual(float(rows[2][0]), 2e-4)
        self.assertEqual(float(rows[2][1]) - float(rows[1][1]), 4.0)
        with open(png_p, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        before = [os.stat(p).st_mtime_ns for p in (csv_p, png_p)]
        rc, _, err = scope_cli("capture", "motor.timer", "--csv", csv_p)
        self.assertOneLine(rc, err, 2, "exists: not replaced")
        rc, _, err = scope_cli("capture", "motor.timer", "--png", png_p)
        self.assertOneLine(rc, err, 2, "exists: not replaced")
        self.assertEqual([os.stat(p).st_mtime_ns for p in (csv_p, png_p)], before)

    def test_capture_a_start_with_then(self) -> None:
        csv_p = os.path.join(OUT, "start.csv")
        try:
            rc, out, err = scope_cli("capture", "motor.state", "motor.vbus", "--trigger", "motor.state", "--level", "1",
                                     "--delay", "10", "--then", "x2c.tune.run=1", "--csv", csv_p, "--force")
        finally:
            stop_motor(ST.t)
        self.assertEqual(rc, 0, err)
        self.assertIn("trigger at dataset 10", out)
        with open(csv_p, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))[1:]
        self.assertEqual([float(r[0]) for r in rows[9:12]], [-5e-5, 0.0, 5e-5])  # time from the trigger
        self.assertEqual([r[1] for r in rows[:11]], ["0"] * 10 + ["1"])

    def test_a_trigger_that_never_comes_should_time_out_and_stop_the_scope(self) -> None:
        rc, _, err = scope_cli("capture", "motor.state", "--trigger", "motor.state", "--level", "3",
                               "--timeout", "0.3")
        self.assertEqual(rc, 1, err)
        self.assertIn("not done within 0.3 s", err.splitlines()[-1])
        self.assertEqual(ST.t.scope_state().state, x2c.SCOPE_IDLE)

    def test_live_headless(self) -> None:
        rc, out, err = scope_cli("live", "motor.timer", "--headless", "--frames", "2")
        self.assertEqual(rc, 0, err)
        self.assertEqual([ln.split(":")[0] for ln in out.splitlines()], ["frame 1", "frame 2"])


class C_Tcp(unittest.TestCase):
    def test_the_same_services_over_tcp(self) -> None:
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        other = Sim("--tcp", str(port))
        try:
            self.assertEqual(other.tcp, f"tcp://127.0.0.1:{port}")
            t = connect(other.tcp)
            try:
                self.assertEqual(t.info.processor_id if t.info else 0, 0x8210)
                kp = var("x2c.tune.cur_kp")
                self.assertTrue(kp.min <= read_var(t, kp.name) <= kp.max)
                cap = t.capture(x2c.ScopeConfig((ch("motor.timer"),)), timeout=5)
                tm = cap.channel(0)
                self.assertEqual(len(tm), ST.size // 4)
                self.assertEqual([b - a for a, b in itertools.pairwise(tm)], [1] * (len(tm) - 1))
            finally:
                t.link.close()
            p = subprocess.run([sys.executable, "-m", "scope", "--port", other.tcp, "info"], capture_output=True,
                               text=True, timeout=60)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("0x8210", p.stdout)
        finally:
            other.stop()


    def test_a_client_leaving_at_any_byte_should_not_wedge_the_target(self) -> None:
        # a device-info request and its reply, whole frames on the wire. A client leaves after
        # k of them (k = 0..all), with a reset so the target's next write fails; another
        # leaves after j bytes of its request: the next client is answered every time
        request = bytes([0x55, 0x01, 0x01, 0x00, 0x57])
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        other = Sim("--tcp", str(port))

        def client() -> socket.socket:
            c = socket.create_connection(("127.0.0.1", port), timeout=5)
            c.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))  # close = reset
            return c

        def whole_reply(c: socket.socket) -> bytes:
            # SYN, SIZE, NODE, DATA[SIZE] (a 0x00 fill after each 0x55 / 0x02 of those), CRC
            got = bytearray(c.recv(1))
            fields: list[int] = []
            while got:
                b = c.recv(1)
                if not b:
                    break
                got += b
                if len(fields) >= 2 and len(fields) == 2 + fields[0]:
                    break  # that was the CRC
                fields.append(b[0])
                if b[0] in (0x55, 0x02):
                    got += c.recv(1)  # its fill
            return bytes(got)

        try:
            c = client()
            c.sendall(request)
            reply = whole_reply(c)
            c.close()
            self.assertEqual(reply[:3], bytes([0x55, 46, 0x01]), reply.hex())  # 46 bytes: service, error, 44
            for k in range(len(reply) + 1):
                c = client()
                c.sendall(request)
                got = b""
                while len(got) < k:
                    got += c.recv(k - len(got))
                c.close()
                c = client()
                c.sendall(request)
                self.assertEqual(whole_reply(c), reply, f"after a client that left at byte {k} of the reply")
                c.close()
            for j in range(1, len(request)):
                c = client()
                c.sendall(request[:j])
                time.sleep(0.05)  # the target's inter-byte timeout passes (simulated time runs faster)
                c.close()
                c = client()
                c.sendall(request)
                self.assertEqual(whole_reply(c), reply, f"after a client that left at byte {j} of its request")
                c.close()
            measured = f"{len(reply) + 1} clients left at every byte of a reply, {len(request) - 1} in a request"
            print("measured: " + measured + ": the next client answered every time")
        finally:
            other.stop()


class C_PtyLeaving(unittest.TestCase):
    def test_a_pty_client_leaving_mid_reply_should_leave_no_stale_reply(self) -> None:
        # the same device-info request on the pseudo-terminal: a client reads k bytes of the reply
        # (k = 0..all) and closes the line; the rest of the reply stays on it. The next client
        # that asks must read its own reply, not the stale tail (a pyx2cscope client, which
        # ignores error codes, would read every later reply one behind). Set up as pyserial
        # does (TCSANOW: no flush of its own)
        request = bytes([0x55, 0x01, 0x01, 0x00, 0x57])
        other = Sim()

        def open_line() -> int:
            fd = os.open(other.pty, os.O_RDWR | os.O_NOCTTY)
            tty.setraw(fd, termios.TCSANOW)  # as pyserial sets a port up: no flush
            return fd

        def read_n(fd: int, n: int, timeout: float = 5.0) -> bytes:
            got = b""
            end = time.monotonic() + timeout
            while len(got) < n and time.monotonic() < end:
                r, _, _ = select.select([fd], [], [], 0.05)
                if r:
                    got += os.read(fd, n - len(got))
            return got

        def read_quiet(fd: int) -> bytes:
            got = read_n(fd, 1)
            while True:
                b = read_n(fd, 1, 0.2)
                if not b:
                    return got
                got += b

        try:
            fd = open_line()
            os.write(fd, request)
            reply = read_quiet(fd)
            os.close(fd)
            self.assertEqual(reply[:3], bytes([0x55, 46, 0x01]), reply.hex())
            for k in range(len(reply) + 1):
                fd = open_line()
                os.write(fd, request)
                self.assertEqual(len(read_n(fd, k)), k)
                time.sleep(0.02)  # the whole reply is on the line
                os.close(fd)
                time.sleep(0.02)  # the next client comes after this one left (a close the target sees)
                fd = open_line()
                os.write(fd, request)
                self.assertEqual(read_n(fd, len(reply)), reply, f"after a client that left at byte {k}")
                self.assertEqual(read_n(fd, 1, 0.1), b"", f"bytes after the reply (left at byte {k})")
                os.close(fd)
            print(f"measured: {len(reply) + 1} pty clients left at every byte of a reply: the next client read "
                  "its own reply every time")
        finally:
            other.stop()


class D_Speed(unittest.TestCase):
    def test_omega_should_match_the_simulators_estimate(self) -> None:
        truth = os.path.join(OUT, "truth.csv")
        if os.path.exists(truth):
            os.remove(truth)
        other = Sim("--truth", truth)
        try:
            t = connect(other.pty)
            try:
                write_var(t, "x2c.tune.speed_ref_rpm", 1000)
                write_var(t, "x2c.tune.run", 1)
                omega = var("motor.smc.omega")
                wait_for("closed loop at 1000 rpm", lambda: read_var(t, "motor.state") == 4
                         and abs(omega.to_eng(read_var(t, "motor.smc.omega")) - 1000) < 20)
                cfg = x2c.ScopeConfig((ch("motor.smc.omega"),), 9)
                cap = t.capture(cfg, timeout=10)
                stop_motor(t)
            finally:
                t.link.close()
        finally:
            other.stop()
        with open(truth, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        last = max(int(r["rec"]) for r in rows)
        by_at = {int(r["at"]): r for r in rows if int(r["rec"]) == last}
        got = [omega.to_eng(x) for x in cap.channel(0)]
        n = ST.size // 2
        self.assertEqual(len(got), n)
        self.assertEqual(sorted(by_at), [2 * i for i in range(n)])
        dev_est = dev_true = 0.0
        sum_true = 0.0
        for i, g in enumerate(got):
            est, true = float(by_at[2 * i]["speed_est_rpm"]), float(by_at[2 * i]["speed_true_rpm"])
            self.assertLessEqual(abs(g - est), 1e-3 * abs(est), f"dataset {i}: {g} rpm vs {est}")
            dev_est = max(dev_est, abs(g - est))
            dev_true = max(dev_true, abs(g - true))
            sum_true += g - true
        # the capture's mean speed is the motor's own (the estimator's ripple averages out)
        mean_true = sum(float(by_at[2 * i]["speed_true_rpm"]) for i in range(n)) / n
        self.assertLessEqual(abs(sum_true / n), 1e-3 * mean_true, "mean of omega vs the true speed")
        t0, t1 = float(by_at[0]["t_s"]), float(by_at[2 * (n - 1)]["t_s"])
        self.assertAlmostEqual(t1 - t0, (n - 1) * 10 / 20000, places=6)  # prescaler 9: every 10th period
        print(f"measured: motor.smc.omega over {len(got)} datasets ({t1 - t0:.4f} s) at 1000 rpm: max |omega - "
              f"speed_est_rpm| {dev_est:.4f} rpm; vs speed_true_rpm mean {sum_true / len(got):+.2f} rpm, "
              f"max |dev| {dev_true:.2f} rpm ({100 * dev_true / 1000:.2f} %)")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        print("usage: e2e_x2c.py <sim executable> <repo root> <output dir>", file=sys.stderr)
        sys.exit(2)
    SIM, ROOT, OUT = sys.argv[1], sys.argv[2], sys.argv[3]
    unittest.main(verbosity=2, argv=[sys.argv[0], *os.environ.get("E2E_ONLY", "").split()])
