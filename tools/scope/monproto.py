"""monproto - host side of the live data monitor protocol (firmware/monitor, docs/monitor.md).

Frame, both directions, little-endian fields:
    0xA5 | LEN | CMD | PAYLOAD[LEN] | CRC16 lo | CRC16 hi
CRC-16/CCITT-FALSE over LEN, CMD and PAYLOAD. A reply has CMD | 0x80, an
error reply CMD 0x7F with [request cmd, error code]; recorded samples come
as unsolicited DATA frames (CMD 0x40).
"""

import struct
import time

SOF = 0xA5
MAX_PAYLOAD = 40
REPLY = 0x80

CMD_INFO = 0x01
CMD_VAR_INFO = 0x02
CMD_PARAM_INFO = 0x03
CMD_SELECT = 0x04
CMD_START = 0x05
CMD_STOP = 0x06
CMD_TRIGGER = 0x07
CMD_STATUS = 0x08
CMD_MOTOR = 0x10
CMD_SET_SPEED = 0x11
CMD_SET_PARAM = 0x12
CMD_DATA = 0x40
CMD_ERROR = 0x7F

ERRORS = {1: "CRC", 2: "LENGTH", 3: "UNKNOWN", 4: "RANGE", 5: "STATE", 6: "TIMEOUT"}

MODE_STREAM, MODE_SNAPSHOT = 0, 1
TRIG_NOW, TRIG_CMD, TRIG_STATE = 0, 1, 2
MOTOR_STOP, MOTOR_START, MOTOR_POT = 0, 1, 2
DATA_LAST, DATA_OVERFLOW = 0x01, 0x02

STATES = ["STOPPED", "CALIBRATE", "LOCK", "OPEN_LOOP", "CLOSED_LOOP", "FAULT"]
STATE_CLOSED_LOOP, STATE_FAULT = STATES.index("CLOSED_LOOP"), STATES.index("FAULT")
KIND_Q15, KIND_INT = 0, 1


def crc16(data, crc=0xFFFF):
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) if crc & 0x8000 else (crc << 1)
            crc &= 0xFFFF
    return crc


def encode(cmd, payload=b""):
    payload = bytes(payload)
    if len(payload) > MAX_PAYLOAD:
        raise ValueError("payload too long")
    body = bytes([len(payload), cmd]) + payload
    c = crc16(body)
    return bytes([SOF]) + body + bytes([c & 0xFF, c >> 8])


class Decoder:
    """Incremental frame decoder: feed bytes, get (cmd, payload) tuples.
    Bytes that do not form a valid frame are skipped (counted in .bad)."""

    def __init__(self):
        self.buf = bytearray()
        self.bad = 0

    def feed(self, data):
        self.buf += data
        out = []
        while True:
            i = self.buf.find(bytes([SOF]))
            if i < 0:
                self.bad += len(self.buf)
                self.buf.clear()
                return out
            if i > 0:
                self.bad += i
                del self.buf[:i]
            if len(self.buf) < 2:
                return out
            n = self.buf[1]
            if n > MAX_PAYLOAD:
                self.bad += 1
                del self.buf[:1]
                continue
            if len(self.buf) < n + 5:
                return out
            frame = bytes(self.buf[: n + 5])
            c = crc16(frame[1 : n + 3])
            if frame[n + 3] != (c & 0xFF) or frame[n + 4] != (c >> 8):
                self.bad += 1
                del self.buf[:1]
                continue
            del self.buf[: n + 5]
            out.append((frame[2], frame[3 : n + 3]))


class Var:
    def __init__(self, idx, kind, fs_milli, name, unit):
        self.idx, self.kind, self.fs, self.name, self.unit = idx, kind, fs_milli / 1000.0, name, unit

    def to_eng(self, raw):
        return raw / 32768.0 * self.fs if self.kind == KIND_Q15 else float(raw)

    def __repr__(self):
        return f"{self.name} [{self.unit or '-'}]"


class Param:
    def __init__(self, idx, value, lo, hi, name):
        self.idx, self.value, self.min, self.max, self.name = idx, value, lo, hi, name


class MonitorError(Exception):
    pass


def max_rate(nch, baud):
    """Sample sets per second a stream of nch channels can carry at baud (8N1)."""
    per_frame = (MAX_PAYLOAD - 4) // (2 * nch)
    frame_bytes = 5 + 4 + per_frame * 2 * nch
    return baud / 10.0 / frame_bytes * per_frame


class Monitor:
    """Talks to the device over a pyserial port (or anything with read/write)."""

    def __init__(self, port, timeout=1.0):
        self.port = port
        self.timeout = timeout
        self.dec = Decoder()
        self.data = []  # DATA frames received while waiting for replies
        self.info = None
        self.vars = []
        self.params = []

    # ---- transport ----
    def _read_frames(self):
        chunk = self.port.read(self.port.in_waiting or 1)
        return self.dec.feed(chunk) if chunk else []

    def request(self, cmd, payload=b""):
        self.port.write(encode(cmd, payload))
        t_end = time.monotonic() + self.timeout
        while time.monotonic() < t_end:
            frames = self._read_frames()
            for k, (c, p) in enumerate(frames):
                if c == CMD_DATA:
                    self.data.append(p)
                elif c == (cmd | REPLY) or (c == CMD_ERROR and len(p) == 2 and p[0] in (cmd, 0)):
                    # frames after the reply in the same read are data for later
                    self.data.extend(q for d, q in frames[k + 1 :] if d == CMD_DATA)
                    if c == CMD_ERROR:
                        raise MonitorError(f"command 0x{cmd:02x}: error {ERRORS.get(p[1], p[1])}")
                    return p
        raise MonitorError(f"command 0x{cmd:02x}: no reply within {self.timeout} s")

    # ---- commands ----
    def connect(self):
        p = self.request(CMD_INFO)
        ver, nvars, nparams, maxch, bufw, fpwm, maxpl = struct.unpack("<BBBBHIB", p[:11])
        self.info = dict(version=ver, nvars=nvars, nparams=nparams, max_ch=maxch, buf_words=bufw,
                         f_pwm=fpwm, max_payload=maxpl)
        self.vars = []
        for i in range(nvars):
            q = self.request(CMD_VAR_INFO, bytes([i]))
            idx, kind, fs = struct.unpack("<BBi", q[:6])
            name, _, unit = q[6:].partition(b"\0")
            self.vars.append(Var(idx, kind, fs, name.decode(), unit.decode()))
        self.params = [self.param_info(i) for i in range(nparams)]
        return self.info

    def var(self, name):
        for v in self.vars:
            if v.name == name:
                return v
        raise MonitorError(f"no variable {name!r}; have {', '.join(v.name for v in self.vars)}")

    def param_info(self, i):
        q = self.request(CMD_PARAM_INFO, bytes([i]))
        idx, val, lo, hi = struct.unpack("<Bhhh", q[:7])
        return Param(idx, val, lo, hi, q[7:].decode())

    def set_param(self, name, value):
        for p in self.params:
            if p.name == name:
                self.request(CMD_SET_PARAM, struct.pack("<Bh", p.idx, int(value)))
                p.value = int(value)
                return
        raise MonitorError(f"no parameter {name!r}")

    def select(self, names, decim):
        idx = [self.var(n).idx for n in names]
        self.request(CMD_SELECT, struct.pack("<HB", decim, len(idx)) + bytes(idx))

    def start(self, mode=MODE_STREAM, trig=TRIG_NOW):
        self.data = []
        self.request(CMD_START, bytes([mode, trig]))

    def stop(self):
        self.request(CMD_STOP)

    def trigger(self):
        self.request(CMD_TRIGGER)

    def status(self):
        p = self.request(CMD_STATUS)
        f = struct.unpack("<BBHB4BHHBBHhhBHH", p[:26])
        return dict(rec=f[0], mode=f[1], decim=f[2], nch=f[3], ch=list(f[4:8]), written=f[8],
                    buffered=f[9], overflow=f[10], state=f[11], fault=f[12], speed_est=f[13],
                    speed_ref=f[14], remote=f[15], rx_errors=f[16], rx_dropped=f[17])

    def motor(self, action):
        self.request(CMD_MOTOR, bytes([action]))

    def set_speed(self, rpm):
        self.request(CMD_SET_SPEED, struct.pack("<h", int(round(rpm))))

    def run_motor(self, rpm):
        """Remote speed reference rpm, then START."""
        self.set_speed(rpm)
        self.motor(MOTOR_START)

    # ---- recorded data ----
    def read_data(self, wait=0.0):
        """DATA frames received so far (and during `wait` seconds more), decoded:
        list of (flags, index, [set, ...]) with each set a tuple of raw int16."""
        t_end = time.monotonic() + wait
        while True:
            for c, p in self._read_frames():
                if c == CMD_DATA:
                    self.data.append(p)
            if time.monotonic() >= t_end:
                break
        out = []
        for p in self.data:
            flags, index, nsets = struct.unpack("<BHB", p[:4])
            vals = struct.unpack(f"<{(len(p) - 4) // 2}h", p[4:])
            nch = len(vals) // nsets if nsets else 0
            out.append((flags, index, [vals[i * nch : (i + 1) * nch] for i in range(nsets)]))
        self.data = []
        return out
