# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""tools/scope without a target: LNet frames (escaping of every field, both inverted checksums,
every size, resynchronisation), the link's errors (no reply, a bad checksum, a reply for another
service, every named error code), the scope's configuration bytes and the client's rotation, the
variable map's reader, and the command's one-line failures (a missing port, an unknown variable
name, a bad map file, an existing --csv / --png).

usage: test_scope.py   (CTest: test_scope, label unit, with the project's .venv python)
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import os
import random
import struct
import sys
import tempfile
import unittest
from collections import deque
from dataclasses import dataclass
from typing import Any

if __name__ == "__main__" and importlib.util.find_spec("yaml") is None:
    print("SKIPPED: pyyaml is not installed (run tools/bootstrap)")
    sys.exit(77)

import yaml

from scope import cli, identify, lnet, varmap, x2c


def frame_of(data: bytes) -> lnet.Frame:
    evs = lnet.Decoder().feed(lnet.encode(data))
    assert len(evs) == 1 and isinstance(evs[0], lnet.Frame), evs
    return evs[0]


class Frames(unittest.TestCase):
    def test_device_info_request_should_be_five_bytes(self) -> None:
        self.assertEqual(lnet.encode(b"\x00"), bytes((0x55, 0x01, 0x01, 0x00, 0x57)))

    def test_every_reserved_byte_should_get_its_fill_in_size_node_and_data(self) -> None:
        # SIZE 0x55 and 0x02, NODE 0x55 and 0x02, DATA 0x55 and 0x02
        for size in (0x55, 0x02):
            wire = lnet.encode(bytes(size))
            self.assertEqual(wire[1:3], bytes((size, 0)))
        for node in (0x55, 0x02):
            wire = lnet.encode(b"\x09", node)
            self.assertEqual(wire[2:4], bytes((node, 0)))
            evs = lnet.Decoder().feed(wire)
            self.assertEqual(evs, [lnet.Frame(node, b"\x09", False)])
        wire = lnet.encode(b"\x0a\x55\x02\x03")
        self.assertEqual(wire[3:9], b"\x0a\x55\x00\x02\x00\x03")
        self.assertEqual(len(wire), 4 + 4 + 2)  # SYN SIZE NODE CRC, the data, two fills

    def test_both_inverted_checksums_should_be_sent_and_taken(self) -> None:
        for raw, sent in ((0x55, 0xAA), (0x02, 0xFD)):
            # SYN + SIZE 2 + NODE 1 + 0x09 + x == raw (mod 256)
            x = (raw - 0x55 - 2 - 1 - 0x09) % 256
            data = bytes((0x09, x))
            wire = lnet.encode(data)
            self.assertEqual(wire[-1], sent, f"sum 0x{raw:02X}")
            f = frame_of(data)
            self.assertTrue(f.crc_inverted)
            self.assertEqual(f.data, data)
            # the raw sum in its place is a bad checksum
            evs = lnet.Decoder().feed(wire[:-1] + bytes((raw,)))
            self.assertFalse(any(isinstance(e, lnet.Frame) for e in evs), evs)

    def test_every_size_should_round_trip_with_random_data(self) -> None:
        rnd = random.Random(16)
        dec = lnet.Decoder()
        for n in range(1, 256):
            data = bytes(rnd.choice((0x55, 0x02, 0x00, rnd.randrange(256))) for _ in range(n))
            self.assertEqual(dec.feed(lnet.encode(data)), [lnet.Frame(1, data, lnet.crc_raw(n, 1, data)
                                                                      in lnet.RESERVED)])

    def test_frames_byte_by_byte_after_noise_should_all_arrive(self) -> None:
        rnd = random.Random(78)
        dec = lnet.Decoder()
        got = 0
        for _ in range(2000):
            noise = bytes(rnd.randrange(256) for _ in range(rnd.randrange(8)))
            data = bytes(rnd.randrange(256) for _ in range(rnd.randrange(1, 20)))
            for b in noise + lnet.encode(data):
                for ev in dec.feed(bytes((b,))):
                    if isinstance(ev, lnet.Frame) and ev.data == data:
                        got += 1
        # a frame is lost only when the noise ended inside a frame that swallowed the SYN
        self.assertGreater(got, 1950)

    def test_a_frame_cut_short_should_not_hide_the_next(self) -> None:
        first = lnet.encode(b"\x09\x01\x02\x03")
        second = lnet.encode(b"\x00")
        for cut in range(1, len(first)):
            evs = lnet.Decoder().feed(first[:cut] + second)
            self.assertIn(lnet.Frame(1, b"\x00", False), evs, f"cut after {cut}")

    def test_a_02_without_its_fill_should_be_a_bad_frame(self) -> None:
        wire = bytearray(lnet.encode(b"\x09\x02\x07"))
        del wire[5]  # the fill after 0x02
        evs = lnet.Decoder().feed(bytes(wire))
        self.assertEqual([type(e) for e in evs], [lnet.BadFrame])
        assert isinstance(evs[0], lnet.BadFrame)
        self.assertEqual(evs[0].why, "fill")

    def test_out_of_range_frames_should_be_refused(self) -> None:
        for data in (b"", bytes(256)):
            with self.assertRaises(ValueError):
                lnet.encode(data)


class Pty(unittest.TestCase):
    def test_a_pty_should_carry_every_byte_value_both_ways_unchanged(self) -> None:
        try:
            master, slave = os.openpty()
        except OSError as e:
            self.skipTest(f"no pseudo-terminal: {e}")
        try:
            name = os.ttyname(slave)
            t = lnet.open_transport(name, 115200)
            self.assertIsInstance(t, lnet.TtyTransport)  # a pty never needs pyserial
            try:
                every = bytes(range(256)) * 2  # XON, XOFF, CR, ^C, ^D ... are data
                os.write(master, every)
                got = b""
                for _ in range(50):
                    got += t.read(0.05)
                    if len(got) >= len(every):
                        break
                self.assertEqual(got, every)
                t.write(every)
                back = b""
                while len(back) < len(every):
                    back += os.read(master, 4096)
                self.assertEqual(back, every)
            finally:
                t.close()
        finally:
            os.close(master)
            os.close(slave)


# ---- the link, against scripted transports ---------------------------------------------------


class Scripted:
    """A transport that answers each write with the next scripted reply (bytes, or None: silence)."""

    def __init__(self, *replies: bytes | None) -> None:
        self.replies: deque[bytes | None] = deque(replies)
        self.sent: list[bytes] = []
        self.pending = b""

    def write(self, data: bytes) -> None:
        self.sent.append(data)
        r = self.replies.popleft() if self.replies else None
        self.pending += r or b""

    def read(self, timeout: float) -> bytes:
        out, self.pending = self.pending, b""
        return out

    def drain(self) -> None:
        self.pending = b""

    def close(self) -> None:
        pass


def reply(*data: int) -> bytes:
    return lnet.encode(bytes(data))


INFO = struct.pack("<HHBH", 5, 1, 255, 0x8210) + b"Nov2520260000Nov2520260000" + struct.pack("<BHII", 4, 0, 0, 0)


class LinkErrors(unittest.TestCase):
    def target(self, *replies: bytes | None) -> tuple[x2c.Target, Scripted]:
        s = Scripted(*replies)
        return x2c.Target(lnet.Link(s, timeout=0.05)), s

    def test_device_info_should_parse_and_set_16_bit_addresses(self) -> None:
        t, s = self.target(lnet.encode(b"\x00\x00" + INFO))
        i = t.device_info()
        self.assertEqual((i.processor_id, i.monitor_version, i.max_frame, i.dsp_state), (0x8210, 5, 255, 4))
        self.assertEqual((i.monitor_date, i.monitor_time), ("Nov252026", "0000"))
        self.assertEqual(s.sent, [bytes((0x55, 1, 1, 0, 0x57))])

    def test_an_unknown_processor_id_should_be_refused_by_name(self) -> None:
        bad = INFO[:5] + struct.pack("<H", 0x1234) + INFO[7:]
        t, _ = self.target(lnet.encode(b"\x00\x00" + bad))
        with self.assertRaisesRegex(x2c.X2CError, "processor id 0x1234 is unknown.*address width"):
            t.device_info()

    def test_no_reply_should_time_out(self) -> None:
        t, _ = self.target(None)
        with self.assertRaisesRegex(lnet.LNetError, "no reply to service 0x00"):
            t.device_info()

    def test_a_bad_checksum_should_be_an_error(self) -> None:
        good = lnet.encode(b"\x01\x00\x04")
        t, _ = self.target(good[:-1] + bytes(((good[-1] + 1) & 0xFF,)))
        with self.assertRaisesRegex(lnet.LNetError, "bad checksum"):
            t.target_state()

    def test_a_reply_for_another_service_should_be_an_error(self) -> None:
        t, _ = self.target(reply(0x09, 0x00, 0x12, 0x34))
        with self.assertRaisesRegex(lnet.LNetError, "reply for service 0x09 .* request for service 0x01"):
            t.target_state()

    def test_every_error_code_should_be_raised_with_its_name(self) -> None:
        for code, name in x2c.ERROR_NAMES.items():
            t, _ = self.target(reply(0x0A, code))
            with self.assertRaises(x2c.TargetError) as cm:
                t.write(0x0800, 2, b"\x01\x00")
            self.assertEqual((cm.exception.code, cm.exception.name, cm.exception.service), (code, name, 0x0A))
            self.assertIn(f"0x{code:02X} ({name}", str(cm.exception))

    def test_a_read_should_go_in_chunks_of_253_bytes(self) -> None:
        replies = [reply(0x09, 0, *([7] * n)) for n in (253, 253, 94)]
        t, s = self.target(*replies)
        self.assertEqual(t.read(0x0900, 600), bytes([7] * 600))
        self.assertEqual([lnet.Decoder().feed(w)[0] for w in s.sent],
                         [lnet.Frame(1, bytes((0x09, a & 0xFF, a >> 8, n, 1)), lnet.crc_raw(5, 1, bytes(
                             (0x09, a & 0xFF, a >> 8, n, 1))) in lnet.RESERVED)
                          for a, n in ((0x0900, 253), (0x09FD, 253), (0x0AFA, 94))])

    def test_a_short_read_reply_should_be_an_error(self) -> None:
        t, _ = self.target(reply(0x09, 0, 1))
        with self.assertRaisesRegex(x2c.X2CError, "1 bytes back, asked for 2"):
            t.read(0x0800, 2, 2)


# ---- the scope's bytes and the rotation ----------------------------------------------------------


class ScopeBytes(unittest.TestCase):
    def test_a_triggered_configuration_should_be_laid_out_as_the_protocol_says(self) -> None:
        cfg = x2c.ScopeConfig((x2c.Channel(0x1102, 2, "S"), x2c.Channel(0x1020, 4, "U")), 3,
                              x2c.Trigger(0x1102, 2, "S", -100, delay=10, rising=False))
        want = (bytes((1, 2, 3, 0)) + bytes((0, 0x02, 0x11, 0, 0, 2)) + bytes((0, 0x20, 0x10, 0, 0, 4))
                + bytes((0x80 | 0x20 | 2, 0, 0x02, 0x11, 0, 0)) + struct.pack("<h", -100)
                + struct.pack("<i", 60) + bytes((0, 1)))
        self.assertEqual(cfg.encode(), want)

    def test_negative_delay_auto_and_float_should_encode(self) -> None:
        cfg = x2c.ScopeConfig((x2c.Channel(0x1000, 4, "F"),), 0, x2c.Trigger(0x1000, 4, "F", 1.5, delay=-3, auto=True))
        b = cfg.encode()
        self.assertEqual(b[10], 0x80 | 0x40 | 0x20 | 4)
        self.assertEqual(struct.unpack("<f", b[16:20])[0], 1.5)
        self.assertEqual(struct.unpack("<i", b[20:24])[0], -12)
        self.assertEqual(b[24:], bytes((1, 0)))

    def test_no_trigger_should_sample_until_full(self) -> None:
        b = x2c.ScopeConfig((x2c.Channel(0x1000, 2),)).encode()
        self.assertEqual(b[0], 2)
        self.assertEqual(len(b), 4 + 6 + 6 + 2 + 4 + 2)

    def test_a_level_that_does_not_fit_should_be_refused(self) -> None:
        cfg = x2c.ScopeConfig((x2c.Channel(0x1000, 1),), 0, x2c.Trigger(0x1000, 1, "U", 300))
        with self.assertRaisesRegex(x2c.X2CError, "does not fit"):
            cfg.encode()

    def test_scope_state_should_read_29_bytes_with_a_signed_delay(self) -> None:
        raw = struct.pack("<BBHIIiiIIB", 0, 2, 0, 480, 0x0900, -24, 0, 480, 480, 0x82)
        st = x2c.ScopeState.parse(raw)
        self.assertEqual((st.trigger_delay, st.buffer_address, st.version, st.done), (-24, 0x0900, 0x82, True))
        with self.assertRaises(x2c.X2CError):
            x2c.ScopeState.parse(raw[:-1])

    def test_rotation_should_put_the_oldest_dataset_first(self) -> None:
        cfg = x2c.ScopeConfig((x2c.Channel(0, 2),), 0, x2c.Trigger(0, 2, "U", 5, delay=3))
        raw = b"".join(struct.pack("<H", i) for i in range(10))
        for trig in range(10):
            st = x2c.ScopeState(0, 1, 0, 20, 0x0900, 6, 2 * trig, 20, 20, 0x82)
            cap = x2c.split_and_rotate(cfg, st, raw)
            self.assertEqual(cap.channel(0)[3], trig, f"trigger at dataset {trig}")
            self.assertEqual(cap.shift, (trig - 3) % 10)
            self.assertEqual(sorted(cap.channel(0)), list(range(10)))
        neg = x2c.ScopeConfig(cfg.channels, 0, x2c.Trigger(0, 2, "U", 5, delay=-3))
        st = x2c.ScopeState(0, 1, 0, 20, 0x0900, -6, 8, 20, 20, 0x82)
        self.assertEqual(x2c.split_and_rotate(neg, st, raw).channel(0), list(range(10)))


# ---- the map ----------------------------------------------------------------------------------------

ROWS = [
    varmap.Var("motor.smc.omega", 0x1102, 2, "S", "int", "rpm", 8000.0),
    varmap.Var("motor.state", 0x1020, 4, "U", "long unsigned int"),
    varmap.Var("motor.smc.valid", 0x110E, 1, "B", "bool"),
    varmap.Var("x2c.tune.cur_kp", 0x0800, 2, "S", "int", "", 0.0, True, 2497, 32767),
]


@dataclass
class VariableInfo:
    """pyx2cscope's VariableInfo fields (pyx2cscope/variable/variable.py), to load as it does."""

    name: str
    type: str
    byte_size: int
    bit_size: int
    bit_offset: int
    address: int
    array_size: int
    valid_values: dict[str, int]


def load_as_pyx2cscope(text: str) -> Any:
    """yaml.load with FullLoader and a !VariableInfo constructor, as pyx2cscope's import_variables."""

    class Loader(yaml.FullLoader):
        pass

    def construct(loader: yaml.FullLoader, node: yaml.MappingNode) -> VariableInfo:
        values: dict[str, Any] = {str(k): v for k, v in loader.construct_mapping(node).items()}
        return VariableInfo(**values)

    Loader.add_constructor("!VariableInfo", construct)
    return yaml.load(text, Loader=Loader)


class Map(unittest.TestCase):
    def test_the_dump_should_load_as_pyx2cscope_loads_it(self) -> None:
        doc = load_as_pyx2cscope(varmap.dump(ROWS))
        self.assertEqual(set(doc), {"variables", "registers", "an1078"})
        v = doc["variables"]["motor.smc.omega"]
        self.assertEqual(v, VariableInfo("motor.smc.omega", "int", 2, 0, 0, 0x1102, 0, {}))
        self.assertEqual(doc["registers"], {})
        self.assertEqual(doc["an1078"]["x2c.tune.cur_kp"],
                         {"unit": "", "full_scale": 0.0, "tunable": True, "min": 2497, "max": 32767})

    def test_the_dump_should_read_back_the_same_rows(self) -> None:
        vm = varmap.parse_map(varmap.dump(ROWS))
        self.assertTrue(vm.has_units)
        self.assertEqual(list(vm.vars.values()), ROWS)
        self.assertAlmostEqual(vm.get("motor.smc.omega").to_eng(4096), 1000.0)
        self.assertEqual(vm.get("motor.state").to_eng(3), 3.0)

    def test_a_map_without_our_key_should_load_without_units(self) -> None:
        doc = yaml.safe_load(varmap.dump(ROWS).replace("!VariableInfo", ""))
        del doc["an1078"]
        vm = varmap.parse_map(yaml.safe_dump(doc))
        self.assertFalse(vm.has_units)
        v = vm.get("motor.smc.omega")
        self.assertEqual((v.unit, v.full_scale, v.tunable, v.kind, v.size), ("", 0.0, False, "S", 2))

    def test_bad_maps_should_be_one_line_errors(self) -> None:
        good = varmap.dump(ROWS)
        for text, want in (("a: [", "not YAML"), ("- 1\n", "no 'variables'"), ("variables: 3\n", "no 'variables'"),
                           (good.replace("type: int", "type: struct foo", 1), "not one this client reads"),
                           (good.replace("byte_size: 2", "byte_size: 4", 1), "do not fit"),
                           (good.replace("address: 4354", "address: x", 1), "not a whole number"),
                           ("variables: {}\n", "no variables")):
            with self.assertRaises(varmap.MapError) as cm:
                varmap.parse_map(text, "m.yml")
            self.assertIn(want, str(cm.exception))
            self.assertNotIn("\n", str(cm.exception))

    def test_an_unknown_name_should_say_so(self) -> None:
        vm = varmap.parse_map(varmap.dump(ROWS))
        with self.assertRaisesRegex(varmap.MapError, "unknown variable 'omega'.*motor.smc.omega"):
            vm.get("omega")


# ---- the command's failures ----------------------------------------------------------------------


class Command(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory()
        self.map = self.path("m.yml")
        with open(self.map, "w", encoding="utf-8") as f:
            f.write(varmap.dump(ROWS))

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def path(self, name: str) -> str:
        return os.path.join(self.tmp.name, name)

    def run_cli(self, *argv: str, opener: cli.Opener | None = None) -> tuple[int, str, str]:
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                rc = cli.main(list(argv), opener) if opener else cli.main(list(argv))
            except SystemExit as e:  # argparse's usage errors
                rc = int(e.code or 0)
        return rc, out.getvalue(), err.getvalue()

    def assertOneLine(self, rc: int, err: str, code: int, *want: str) -> None:
        self.assertEqual(rc, code, err)
        self.assertEqual(len(err.splitlines()), 1, err)
        self.assertTrue(err.startswith("scope: "), err)
        self.assertNotIn("Traceback", err)
        for w in want:
            self.assertIn(w, err)

    def test_list_should_show_address_type_access_range_and_unit(self) -> None:
        rc, out, err = self.run_cli("--map", self.map, "list")
        self.assertEqual(rc, 0, err)
        line = next(ln for ln in out.splitlines() if ln.startswith("x2c.tune.cur_kp"))
        self.assertEqual(line.split()[1:4], ["0x0800", "int", "RW"])
        self.assertIn("2497..32767", line)
        self.assertIn("rpm (8000 rpm = 32768)", out)

    def test_a_missing_port_should_be_one_line(self) -> None:
        rc, _, err = self.run_cli("--port", self.path("no-such-tty"), "info")
        self.assertOneLine(rc, err, 1, "cannot open port", "No such file")
        rc, _, err = self.run_cli("--port", self.map, "info")
        self.assertOneLine(rc, err, 1, "not a terminal")
        rc, _, err = self.run_cli("--map", self.map, "read", "motor.state")
        self.assertOneLine(rc, err, 2, "needs --port")
        rc, _, err = self.run_cli("--port", "tcp://127.0.0.1:1", "info")
        self.assertOneLine(rc, err, 1, "cannot connect to 127.0.0.1:1")

    def test_an_unknown_variable_should_be_one_line_before_the_port_opens(self) -> None:
        for argv in (("read", "motor.nope"), ("write", "nope", "1"), ("capture", "motor.state", "--trigger", "nope")):
            rc, _, err = self.run_cli("--port", self.path("no-such-tty"), "--map", self.map, *argv)
            self.assertOneLine(rc, err, 2, "unknown variable")

    def test_a_bad_map_file_should_be_one_line(self) -> None:
        bad = self.path("bad.yml")
        for text in ("variables: [1, 2]\n", "\x00\x01 :", "variables:\n  x: !VariableInfo {address: 1}\n"):
            with open(bad, "w", encoding="utf-8") as f:
                f.write(text)
            rc, _, err = self.run_cli("--map", bad, "list")
            self.assertOneLine(rc, err, 1, "--map")
        rc, _, err = self.run_cli("--map", self.path("none.yml"), "list")
        self.assertOneLine(rc, err, 1, "No such file")
        rc, _, err = self.run_cli("list")
        self.assertOneLine(rc, err, 2, "needs --map")

    def test_an_existing_csv_or_png_should_not_be_replaced(self) -> None:
        for opt, name in (("--csv", "c.csv"), ("--png", "p.png")):
            p = self.path(name)
            with open(p, "w", encoding="utf-8") as f:
                f.write("keep")
            rc, _, err = self.run_cli("--port", self.path("no-such-tty"), "--map", self.map, "capture",
                                      "motor.smc.omega", opt, p)
            self.assertOneLine(rc, err, 2, "exists: not replaced", "--force")
            with open(p, encoding="utf-8") as f:
                self.assertEqual(f.read(), "keep")
        # with --force the file check passes and the port is what fails
        rc, _, err = self.run_cli("--port", self.path("no-such-tty"), "--map", self.map, "capture",
                                  "motor.smc.omega", "--csv", self.path("c.csv"), "--force")
        self.assertOneLine(rc, err, 1, "cannot open port")

    def test_bad_capture_options_should_be_usage_errors(self) -> None:
        base = ("--port", self.path("none"), "--map", self.map, "capture")
        for argv, want in (((*base, "motor.state", "--delay", "3"), "only with --trigger"),
                           ((*base, "motor.state", "--png", self.path("x.jpg")), "must end in .png"),
                           ((*base, *(["motor.state"] * 9)), "1..8 channels"),
                           ((*base, "motor.state", "--trigger", "motor.smc.omega", "--level", "9000"), "outside"),
                           ((*base, "motor.state", "--trigger", "motor.state", "--level", "0.5"), "whole number"),
                           ((*base, "motor.state", "--prescaler", "-1"), "outside"),
                           (("--port", "x", "--map", self.map, "write", "x2c.tune.cur_kp", "1.5"), "not a whole"),
                           (("--port", "x", "--map", self.map, "write", "x2c.tune.cur_kp", "40000"), "does not fit"),
                           (("frobnicate",), "invalid choice")):
            rc, _, err = self.run_cli(*argv)
            self.assertOneLine(rc, err, 2, want)

    def test_a_refused_write_should_exit_1_naming_the_code(self) -> None:
        def opener(port: str, baud: int) -> lnet.Transport:
            return Scripted(lnet.encode(b"\x00\x00" + INFO), reply(0x0A, 0x42), reply(0x09, 0, 0x0E, 0x4E))

        rc, out, err = self.run_cli("--port", "fake", "--map", self.map, "write", "x2c.tune.cur_kp", "1",
                                    opener=opener)
        self.assertOneLine(rc, err, 1, "0x42 (limit", "it reads 19982")
        self.assertEqual(out, "")

    def test_a_corrupt_reply_should_be_one_line(self) -> None:
        def opener(port: str, baud: int) -> lnet.Transport:
            good = lnet.encode(b"\x00\x00" + INFO)
            return Scripted(good[:-1] + bytes(((good[-1] ^ 1),)))

        rc, _, err = self.run_cli("--port", "fake", "info", opener=opener)
        self.assertOneLine(rc, err, 1, "bad checksum")


class JudgeIdentification(unittest.TestCase):
    """an1078-identify writes a description only of a finished, fault-free, physically possible
    result: each field glitched (x0, x0.1, x10, the saturated code) through identify.judge."""

    # the Hurst as the firmware reports it (docs/identify.md)
    GOOD = identify.Result(status=identify.STATUS_DONE, error=0, rs_uohm=2_670_000, ls_nh=1_920_000,
                           ke_uv_per_rpm=7_300, j_ng_m2=7_500, deadtime_ns=1_990, ld_nh=1_900_000,
                           lq_nh=1_940_000, pole_pairs=5)

    def refused(self, r: identify.Result, fragment: str, state: str = "STOPPED", fault: int = 0) -> None:
        with self.assertRaises(lnet.LNetError) as cm:
            identify.judge(r, state, fault, "a fault")
        self.assertIn(fragment, str(cm.exception))

    def test_a_good_result_should_pass(self) -> None:
        identify.judge(self.GOOD, "STOPPED", 0)

    def test_done_with_an_error_or_in_fault_should_be_refused(self) -> None:
        from dataclasses import replace
        self.refused(replace(self.GOOD, error=3), "DONE with error code 3")
        self.refused(self.GOOD, "FAULT", state="FAULT", fault=2)
        self.refused(self.GOOD, "fault a fault", fault=2)

    def test_each_glitched_field_should_be_refused(self) -> None:
        from dataclasses import replace
        cases = [("pole_pairs", 0, "pole pairs 0"), ("pole_pairs", 255, "pole pairs 255"),
                 ("rs_uohm", 0, "rs_uohm 0"), ("ke_uv_per_rpm", 0, "ke_uv_per_rpm 0"),
                 ("ls_nh", 0, "ls_nh 0"), ("deadtime_ns", 0, "dead time 0"),
                 ("deadtime_ns", 1_990_000, "dead time"),
                 ("ls_nh", 19_200_000, "one of them is corrupt"), ("ls_nh", 192_000, "one of them is corrupt"),
                 ("ld_nh", 19_000_000, "one of them is corrupt"), ("lq_nh", 194_000, "one of them is corrupt")]
        for f in ("rs_uohm", "ls_nh", "ke_uv_per_rpm", "j_ng_m2", "deadtime_ns", "ld_nh", "lq_nh"):
            cases.append((f, 0xFFFFFFFF, "saturated"))
        for f, v, fragment in cases:
            with self.subTest(f"{f} = {v}"):
                self.refused(replace(self.GOOD, **{f: v}), fragment)


if __name__ == "__main__":
    unittest.main(verbosity=1, argv=[sys.argv[0]])
