"""Host side of the monitor protocol (tools/scope/monproto.py): CRC, encoding, the incremental
decoder's resynchronisation, the bandwidth table; the core's state and fault names
(tools/scope/mc_names.py, read by tools/scope and tools/sim/plot.py). The firmware side is
test_monitor.c."""

import random
import struct
import unittest

from scope import mc_names
from scope import monproto as mp


class MonprotoTest(unittest.TestCase):
    def test_crc_should_give_the_ccitt_false_check_value(self) -> None:
        self.assertEqual(mp.crc16(b"123456789"), 0x29B1)

    def test_encode_should_frame_len_cmd_payload_and_a_little_endian_crc(self) -> None:
        f = mp.encode(mp.CMD_SET_SPEED, struct.pack("<h", 2000))
        self.assertEqual(f[:5], bytes([0xA5, 2, 0x11, 0xD0, 0x07]))
        c = mp.crc16(f[1:5])
        self.assertEqual(f[5:], bytes([c & 0xFF, c >> 8]))
        with self.assertRaises(ValueError):
            mp.encode(1, bytes(41))

    def test_decoder_should_resynchronise_after_noise_and_corrupt_frames(self) -> None:
        rng = random.Random(7)
        good = [mp.encode(0x40 + i % 3, bytes(rng.randrange(256) for _ in range(rng.randrange(41))))
                for i in range(200)]
        stream = bytearray()
        for g in good:
            stream += bytes(rng.randrange(256) for _ in range(rng.randrange(4)))  # noise
            bad = bytearray(g)
            bad[rng.randrange(1, len(bad))] ^= 0x5A  # a corrupted copy first
            stream += bad + g
        d = mp.Decoder()
        got: list[tuple[int, bytes]] = []
        for i in range(0, len(stream), 7):  # fed in small chunks
            got += d.feed(bytes(stream[i:i + 7]))
        frames = [mp.encode(c, p) for c, p in got]
        # every good frame comes out; a corrupted copy may only come out if it became a valid frame
        it = iter(frames)
        for g in good:
            self.assertIn(g, it)
        self.assertGreater(d.bad, 0)

    def test_max_rate_should_match_the_documented_table(self) -> None:
        self.assertAlmostEqual(mp.max_rate(4, 38400), 3840.0 / 41 * 4, places=6)  # 41-byte frames of 4 sets
        self.assertAlmostEqual(mp.max_rate(1, 38400), 3840.0 / 45 * 18, places=6)  # 45-byte frames of 18 sets
        self.assertAlmostEqual(mp.max_rate(2, 115200), 11520.0 / 45 * 9, places=6)

    def test_var_should_convert_q15_to_engineering_units(self) -> None:
        v = mp.Var(2, mp.KIND_Q15, 8000000, "speed_est", "rpm")
        self.assertAlmostEqual(v.to_eng(8192), 2000.0)
        self.assertAlmostEqual(v.to_eng(-32768), -8000.0)
        self.assertEqual(mp.Var(0, mp.KIND_INT, 1000, "state", "").to_eng(4), 4.0)


class McNamesTest(unittest.TestCase):
    def test_the_names_should_be_firmware_mc_h_lists_in_order(self) -> None:
        n = mc_names.read()
        self.assertEqual(n.states[0], "STOPPED")
        self.assertIn("CLOSED_LOOP", n.states)
        self.assertEqual(n.states[-1], "FAULT")
        self.assertEqual(n.faults[0], "none")
        self.assertEqual(n.fault(1), "OVERCURRENT")
        self.assertEqual(n.fault(999), "999")
        self.assertEqual(n.state(-1), "unknown state -1")
        self.assertEqual(mp.STATES, n.states)

    def test_a_table_should_be_read_with_its_comments_and_any_spacing(self) -> None:
        text = ("#define MC_STATE_LIST(X) \\\n    X(A) /* a, X(B) in a comment */ \\\n    X(C)\n\n"
                "#define MC_FAULT_LIST(X) X(NONE,0) \\\n  X(ONE, 1)   /* one */\n")
        n = mc_names.parse(text)
        self.assertEqual(n.states, ("A", "C"))
        self.assertEqual(n.faults, ("none", "ONE"))
        with self.assertRaises(mc_names.McNamesError):
            mc_names.parse("#define MC_STATE_LIST(X) X(A)\n")
        with self.assertRaises(mc_names.McNamesError):
            mc_names.parse("#define MC_STATE_LIST(X) X(A)\n#define MC_FAULT_LIST(X) X(NONE, 0) X(TWO, 2)\n")


if __name__ == "__main__":
    unittest.main(verbosity=2)
