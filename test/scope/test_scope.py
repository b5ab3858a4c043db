"""tools/scope against a fake device: short, corrupt, garbled and missing replies, a port that fails,
bad ports, options and output paths. Whatever goes wrong, the tool ends with exactly one line on
stderr and a non-zero exit status (never a traceback), resends a request only where the protocol
allows it, and never writes a file it was not asked to write (nor half of one it was).

usage: test_scope.py   (CTest: test_scope, with the project's .venv python)
"""

import contextlib
import io
import os
import struct
import subprocess
import sys
import tempfile
import time
import unittest
from collections.abc import Callable

from scope import cli as scope
from scope import monproto as mp

HERE = os.path.dirname(os.path.abspath(__file__))
SCOPE_DIR = os.path.join(HERE, "..", "..", "tools", "scope")

F_PWM = 20000
VARS = [("speed_est", "rpm", 8_000_000), ("speed_ref", "rpm", 8_000_000), ("iq", "A", 4_400), ("id", "A", 4_400)]
RPM_Q15 = round(2000 * 32768 / 8000)  # 2000 rpm on the 8000 rpm scale

# A reply mutator: (request cmd, the reply frame the device would send) -> the bytes it sends.
Mutator = Callable[[int, bytes], bytes]


class FakeDevice:
    """The firmware monitor's side of the protocol, enough for tools/scope: three variables, one
    parameter, a stream of DATA frames after START, a motor that is in closed loop at once."""

    def __init__(self, mutate: Mutator | None = None) -> None:
        self.dec = mp.Decoder()
        self.mutate = mutate
        self.seen: list[tuple[int, bytes]] = []  # requests, in order
        self.nch = 1
        self.streaming = False
        self.index = 0
        self.data_mutate: Callable[[bytes], bytes] | None = None

    def frame(self, cmd: int, payload: bytes) -> bytes:
        out = mp.encode(cmd, payload)
        return self.mutate(cmd & 0x7F if cmd != mp.CMD_DATA else cmd, out) if self.mutate else out

    def reply(self, cmd: int, payload: bytes = b"") -> bytes:
        return self.frame(cmd | mp.REPLY, payload)

    def handle(self, cmd: int, p: bytes) -> bytes:
        self.seen.append((cmd, p))
        if cmd == mp.CMD_INFO:
            return self.reply(cmd, struct.pack("<BBBBHIB", 1, len(VARS), 1, 4, 256, F_PWM, 40))
        if cmd == mp.CMD_VAR_INFO:
            name, unit, fs = VARS[p[0]]
            return self.reply(cmd, struct.pack("<BBi", p[0], mp.KIND_Q15, fs) + name.encode() + b"\0" + unit.encode())
        if cmd == mp.CMD_PARAM_INFO:
            return self.reply(cmd, struct.pack("<Bhhh", 0, 1000, 125, 8000) + b"cur_kp")
        if cmd == mp.CMD_SELECT:
            self.nch = p[2]
            return self.reply(cmd)
        if cmd == mp.CMD_START:
            self.streaming, self.index = True, 0
            return self.reply(cmd, bytes(4))
        if cmd == mp.CMD_STOP:
            self.streaming = False
            return self.reply(cmd)
        if cmd == mp.CMD_STATUS:
            return self.reply(cmd, struct.pack("<BBHB4BHHBBHhhBHH", 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0,
                                               mp.STATE_CLOSED_LOOP, 0, RPM_Q15, RPM_Q15, 1, 0, 0))
        return self.reply(cmd)  # MOTOR, SET_SPEED, SET_PARAM

    def data_frame(self) -> bytes:
        per = (mp.MAX_PAYLOAD - 4) // (2 * self.nch)
        vals = [RPM_Q15 + k for k in range(per * self.nch)]
        p = struct.pack("<BHB", 0, self.index & 0xFFFF, per) + struct.pack(f"<{len(vals)}h", *vals)
        self.index += per
        if self.data_mutate is not None:
            p = self.data_mutate(p)
        return self.frame(mp.CMD_DATA, p)


class FakePort:
    """A pyserial stand-in wired to a FakeDevice (or to nothing: a silent line)."""

    def __init__(self, dev: FakeDevice | None, garbage: bytes = b"", fail_reads_after: int = -1) -> None:
        self.dev = dev
        self.rx = bytearray(garbage)
        self.reads = 0
        self.fail_reads_after = fail_reads_after
        self.closed = False

    @property
    def in_waiting(self) -> int:
        return len(self.rx)

    def write(self, data: bytes, /) -> int:
        if self.dev is not None:
            for cmd, p in self.dev.dec.feed(bytes(data)):
                self.rx += self.dev.handle(cmd, p)
        return len(data)

    def read(self, size: int = 1) -> bytes:
        self.reads += 1
        if 0 <= self.fail_reads_after < self.reads:
            raise OSError(5, "Input/output error (the adapter was unplugged)")
        if not self.rx and self.dev is not None and self.dev.streaming:
            self.rx += self.dev.data_frame()
        if not self.rx:
            time.sleep(0.001)  # a port's read timeout, short
            return b""
        out = bytes(self.rx[:size])
        del self.rx[:size]
        return out

    def close(self) -> None:
        self.closed = True


def run(argv: list[str], port: FakePort | None = None) -> tuple[int, str, str, bool]:
    """tools/scope's main() in this process: (exit status, stdout, stderr, port opened)."""
    out, err = io.StringIO(), io.StringIO()
    opened = []

    def opener(args: object) -> FakePort:
        opened.append(True)
        assert port is not None
        return port

    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = scope.main(argv, opener=opener)
        except SystemExit as e:  # argparse's refusal
            code = e.code if isinstance(e.code, int) else 1
    return code, out.getvalue(), err.getvalue(), bool(opened)


FAST = ["--reply-timeout", "0.05"]


def short(cmd_to_cut: int, keep: int) -> Mutator:
    """Cuts the reply to one command to `keep` payload bytes, with a valid CRC (a foreign or broken
    firmware, not line noise)."""

    def m(cmd: int, frame: bytes) -> bytes:
        if cmd != cmd_to_cut:
            return frame
        return mp.encode(frame[2], frame[3 : 3 + keep])

    return m


class ScopeFailsInOneLine(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory(prefix="test_scope_")
        self.dir = self.tmp.name

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def assertOneLine(self, err: str, *want: str) -> None:
        self.assertNotIn("Traceback", err)
        self.assertEqual(err.count("\n"), 1, f"want exactly one line on stderr, got {err!r}")
        self.assertTrue(err.startswith("scope: "), err)
        for w in want:
            self.assertIn(w, err)

    def path(self, name: str) -> str:
        return os.path.join(self.dir, name)

    def existing(self, name: str) -> str:
        p = self.path(name)
        with open(p, "w") as f:
            f.write("an earlier recording\n")
        return p

    def assertUntouched(self, p: str) -> None:
        with open(p) as f:
            self.assertEqual(f.read(), "an earlier recording\n")
        self.assertEqual([n for n in os.listdir(self.dir) if n.startswith(".scope-")], [], "a temporary left behind")

    # ---- the fake device itself: a clean session works ----
    def test_a_clean_headless_session_should_write_the_csv_and_png(self) -> None:
        dev = FakeDevice()
        csv_path, png_path = self.path("run.csv"), self.path("run.png")
        code, _out, err, _ = run(["--port", "fake", "--headless", "--channels", "speed_est,iq", "--decim", "100",
                                 "--duration", "0.1", "--start-rpm", "2000", "--settle", "0", "--stop",
                                 "--csv", csv_path, "--png", png_path], FakePort(dev))
        self.assertEqual((code, err), (0, ""))
        with open(csv_path) as f:
            rows = f.read().splitlines()
        self.assertEqual(rows[0], "index,t_s,speed_est_rpm,iq_A,speed_est_raw,iq_raw")
        self.assertEqual(len(rows), 1 + 20)  # 0.1 s at 20 kHz / 100
        with open(png_path, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertIn((mp.CMD_MOTOR, bytes([mp.MOTOR_STOP])), dev.seen)

    def test_written_files_should_get_the_umask_or_keep_their_mode(self) -> None:
        old = os.umask(0o022)
        try:
            csv_path, png_path = self.path("new.csv"), self.existing("old.png")
            os.chmod(png_path, 0o640)
            code, _, err, _ = run(["--port", "fake", "--headless", "--channels", "speed_est", "--decim", "100",
                                   "--duration", "0.05", "--csv", csv_path, "--png", png_path],
                                  FakePort(FakeDevice()))
            self.assertEqual((code, err), (0, ""))
            self.assertEqual(os.stat(csv_path).st_mode & 0o777, 0o644)  # a new file: 0666 less the umask
            self.assertEqual(os.stat(png_path).st_mode & 0o777, 0o640)  # a replaced one keeps its mode
        finally:
            os.umask(old)

    # ---- short, corrupt and missing replies ----
    def test_a_short_info_reply_should_end_in_one_line_and_leave_the_csv_alone(self) -> None:
        csv_path = self.existing("run.csv")
        code, _, err, _ = run(["--port", "fake", "--headless", "--csv", csv_path] + FAST,
                              FakePort(FakeDevice(short(mp.CMD_INFO, 5))))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "command 0x01: corrupt reply: 5 bytes")
        self.assertUntouched(csv_path)

    def test_a_short_status_reply_should_end_in_one_line_and_stop_the_motor(self) -> None:
        dev = FakeDevice(short(mp.CMD_STATUS, 10))
        code, _, err, _ = run(["--port", "fake", "--headless", "--start-rpm", "2000", "--stop"] + FAST,
                              FakePort(dev))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "command 0x08: corrupt reply: 10 bytes")
        self.assertEqual(dev.seen[-1], (mp.CMD_MOTOR, bytes([mp.MOTOR_STOP])), "--stop on a failure")

    def test_a_silent_device_should_be_asked_three_times_then_end_in_one_line(self) -> None:
        t0 = time.monotonic()
        code, _, err, _ = run(["--port", "fake", "--list"] + FAST, FakePort(None))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "command 0x01: no reply within 0.05 s (sent 3 times)")
        self.assertLess(time.monotonic() - t0, 2.0)

    def test_garbage_only_should_end_in_one_line(self) -> None:
        noise = bytes((k * 37 + 11) & 0xFF for k in range(3000)).replace(b"\xa5", b"\x00")
        code, _, err, _ = run(["--port", "fake", "--list"] + FAST, FakePort(None, garbage=noise))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "no reply")

    def test_garbage_before_the_replies_should_be_skipped(self) -> None:
        noise = b"\x00\xa5\x30\xff" * 50  # a SOF with an impossible LEN among it
        code, out, err, _ = run(["--port", "fake", "--list"] + FAST, FakePort(FakeDevice(), garbage=noise))
        self.assertEqual((code, err), (0, ""))
        self.assertIn("speed_est", out)

    def test_a_bad_checksum_once_should_be_resent_and_then_work(self) -> None:
        hit: list[int] = []

        def once(cmd: int, frame: bytes) -> bytes:
            if cmd == mp.CMD_VAR_INFO and not hit:
                hit.append(1)
                return frame[:-1] + bytes([frame[-1] ^ 0xFF])
            return frame

        port = FakePort(FakeDevice(once))
        mon = mp.Monitor(port, timeout=0.05)
        mon.connect()
        self.assertEqual([v.name for v in mon.vars], [v[0] for v in VARS])
        self.assertEqual(mon.resends, 1)

    def test_a_bad_checksum_every_time_should_end_in_one_line(self) -> None:
        def always(cmd: int, frame: bytes) -> bytes:
            return frame[:-1] + bytes([frame[-1] ^ 0xFF])

        code, _, err, _ = run(["--port", "fake", "--list"] + FAST, FakePort(FakeDevice(always)))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "command 0x01: no reply", "sent 3 times")

    def test_a_lost_motor_start_reply_should_not_be_resent(self) -> None:
        def drop(cmd: int, frame: bytes) -> bytes:
            return b"" if cmd == mp.CMD_MOTOR else frame

        dev = FakeDevice(drop)
        code, _, err, _ = run(["--port", "fake", "--headless", "--start-rpm", "2000"] + FAST, FakePort(dev))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "command 0x10: no reply within 0.05 s")
        self.assertEqual(sum(1 for c, _ in dev.seen if c == mp.CMD_MOTOR), 1, "START could run twice")

    def test_a_crc_error_reply_should_resend_even_a_motor_start(self) -> None:
        hit: list[int] = []

        def crc_error(cmd: int, frame: bytes) -> bytes:
            if cmd == mp.CMD_MOTOR and not hit:
                hit.append(1)  # the device saw a corrupted request: it changed nothing
                return mp.encode(mp.CMD_ERROR, bytes([mp.CMD_MOTOR, mp.ERR_CRC]))
            return frame

        mon = mp.Monitor(FakePort(FakeDevice(crc_error)), timeout=0.05)
        mon.motor(mp.MOTOR_START)
        self.assertEqual(mon.resends, 1)

    def test_a_range_error_reply_should_end_in_one_line_without_a_resend(self) -> None:
        def rng(cmd: int, frame: bytes) -> bytes:
            return mp.encode(mp.CMD_ERROR, bytes([cmd, mp.ERR_RANGE])) if cmd == mp.CMD_SET_PARAM else frame

        dev = FakeDevice(rng)
        code, _, err, _ = run(["--port", "fake", "--headless", "--set", "cur_kp=1"] + FAST, FakePort(dev))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "command 0x12: error RANGE")
        self.assertEqual(sum(1 for c, _ in dev.seen if c == mp.CMD_SET_PARAM), 1)

    def test_a_data_frame_of_the_wrong_size_should_end_in_one_line(self) -> None:
        dev = FakeDevice()
        dev.data_mutate = lambda p: p[:-1]  # one byte short of its sets
        csv_path = self.existing("run.csv")
        code, _, err, _ = run(["--port", "fake", "--headless", "--decim", "100", "--csv", csv_path] + FAST,
                              FakePort(dev))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "corrupt DATA frame")
        self.assertUntouched(csv_path)

    def test_corrupt_info_and_var_info_contents_should_end_in_one_line(self) -> None:
        def zero_pwm(cmd: int, frame: bytes) -> bytes:
            return mp.encode(frame[2], struct.pack("<BBBBHIB", 1, 4, 1, 4, 256, 0, 40)) if cmd == mp.CMD_INFO else frame

        def bad_name(cmd: int, frame: bytes) -> bytes:
            return mp.encode(frame[2], frame[3:9] + b"\xff\xfe\0rpm") if cmd == mp.CMD_VAR_INFO else frame

        def wrong_index(cmd: int, frame: bytes) -> bytes:
            return mp.encode(frame[2], bytes([7]) + frame[4:-2]) if cmd == mp.CMD_VAR_INFO else frame

        for mut, want in ((zero_pwm, "corrupt INFO reply"), (bad_name, "corrupt VAR_INFO 0 name"),
                          (wrong_index, "corrupt VAR_INFO reply for variable 0")):
            with self.subTest(want):
                code, _, err, _ = run(["--port", "fake", "--list"] + FAST, FakePort(FakeDevice(mut)))
                self.assertEqual(code, 1)
                self.assertOneLine(err, want)

    def test_a_port_that_fails_mid_session_should_end_in_one_line(self) -> None:
        code, _, err, _ = run(["--port", "fake", "--list"] + FAST, FakePort(FakeDevice(), fail_reads_after=3))
        self.assertEqual(code, 1)
        self.assertOneLine(err, "reading the port failed", "Input/output error")

    # ---- ports, options, output paths ----
    def test_a_bad_port_should_end_in_one_line(self) -> None:
        for port in (self.path("no-such-tty"), self.dir, os.devnull):
            with self.subTest(port):
                p = subprocess.run([sys.executable, SCOPE_DIR, "--port", port, "--list"], capture_output=True,
                                   text=True, timeout=60)
                self.assertEqual(p.returncode, 1)
                self.assertOneLine(p.stderr, "cannot open port")

    def test_bad_options_should_be_refused_in_one_line_before_the_port_opens(self) -> None:
        cases = [["--duration", "nan"], ["--duration", "inf"], ["--duration", "1e300"], ["--baud", "0"],
                 ["--baud", "9600.5"], ["--decim", "20000"], ["--decim", "-1"], ["--start-rpm", "inf"],
                 ["--start-rpm", "40000"], ["--window", "nan"], ["--reply-timeout", "0"], ["--set", "cur_kp"],
                 ["--set", "cur_kp=abc"], ["--set", "=5"], ["--frob"], ["--baud", "+-5"],
                 ["--set", "cur_kp=99999999999"], ["--set", "cur_kp=0x10"], ["--set", "cur_kp=40000"]]
        for extra in cases:
            with self.subTest(extra):
                code, _, err, opened = run(["--port", "fake"] + extra, FakePort(FakeDevice()))
                self.assertEqual(code, 2)
                self.assertOneLine(err)
                self.assertFalse(opened)

    def test_bad_output_paths_should_be_refused_before_the_port_opens(self) -> None:
        os.mkdir(self.path("adir"))
        cases = [
            (["--csv", self.path("missing/run.csv")], "no folder"),
            (["--csv", self.path("adir")], "not a regular file"),
            (["--csv", os.devnull], "not a regular file"),
            (["--png", self.path("run.csv")], "must end in .png"),
            (["--png", self.path("run")], "must end in .png"),
            (["--csv", self.path("same.png"), "--png", self.path("same.png")], "the same file"),
            (["--csv", ""], "empty file name"),
        ]
        for extra, want in cases:
            with self.subTest(extra):
                code, _, err, opened = run(["--port", "fake", "--headless"] + extra, FakePort(FakeDevice()))
                self.assertEqual(code, 2)
                self.assertOneLine(err, want)
                self.assertFalse(opened)
        code, _, err, opened = run(["--port", "fake", "--png", self.path("a.png")], FakePort(FakeDevice()))
        self.assertEqual(code, 2)
        self.assertOneLine(err, "--png: only with --headless")


if __name__ == "__main__":
    unittest.main(verbosity=2)
