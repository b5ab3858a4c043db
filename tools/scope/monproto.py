"""monproto - host side of the live data monitor protocol (firmware/monitor, docs/monitor.md).

Frame, both directions, little-endian fields:
    0xA5 | LEN | CMD | PAYLOAD[LEN] | CRC16 lo | CRC16 hi
CRC-16/CCITT-FALSE over LEN, CMD and PAYLOAD. A reply has CMD | 0x80, an
error reply CMD 0x7F with [request cmd, error code]; recorded samples come
as unsolicited DATA frames (CMD 0x40).

Everything the device sends is checked before it is used: a reply that is
missing, shorter than its command's layout, or inconsistent (a VAR_INFO for
another index, a DATA frame whose size does not match the channels selected)
raises MonitorError with one line saying what was wrong; so does a port that
fails under it. A request is sent again, up to `retries` times, when the
protocol says that is safe (docs/monitor.md, "Host side").
"""

import math
import struct
import time
from typing import Protocol, TypedDict

from scope import mc_names

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

ERR_CRC, ERR_LENGTH, ERR_UNKNOWN, ERR_RANGE, ERR_STATE, ERR_TIMEOUT = 1, 2, 3, 4, 5, 6
ERRORS = {ERR_CRC: "CRC", ERR_LENGTH: "LENGTH", ERR_UNKNOWN: "UNKNOWN", ERR_RANGE: "RANGE",
          ERR_STATE: "STATE", ERR_TIMEOUT: "TIMEOUT"}

MODE_STREAM, MODE_SNAPSHOT = 0, 1
TRIG_NOW, TRIG_CMD, TRIG_STATE = 0, 1, 2
MOTOR_STOP, MOTOR_START, MOTOR_POT = 0, 1, 2
DATA_LAST, DATA_OVERFLOW = 0x01, 0x02

STATES = mc_names.read().states
STATE_CLOSED_LOOP, STATE_FAULT = STATES.index("CLOSED_LOOP"), STATES.index("FAULT")
KIND_Q15, KIND_INT = 0, 1

DECIM_MAX = 10000  # SELECT's decimation range, 1..10000 (docs/monitor.md)

# The shortest reply payload each command's layout allows (docs/monitor.md's table); longer is
# accepted (a newer firmware may append fields), shorter is a corrupt or foreign reply.
REPLY_MIN_LEN = {CMD_INFO: 11, CMD_VAR_INFO: 8, CMD_PARAM_INFO: 8, CMD_START: 4, CMD_STATUS: 26}

# Requests that leave the device in the same state however many times it gets them: after a
# lost reply (no answer within the timeout) they are sent again. The others (START, TRIGGER,
# MOTOR) are sent again only after an error reply that says the request never got through
# whole (CRC, LENGTH, TIMEOUT): "a request that gets an error reply has changed nothing".
IDEMPOTENT = frozenset({CMD_INFO, CMD_VAR_INFO, CMD_PARAM_INFO, CMD_STATUS, CMD_STOP, CMD_SELECT,
                        CMD_SET_SPEED, CMD_SET_PARAM})
TRANSPORT_ERRORS = frozenset({ERR_CRC, ERR_LENGTH, ERR_TIMEOUT})

# The device drops a truncated frame after 20 ms without a byte; a resend waits this long first
# so that the two never merge into one frame.
RESEND_GAP_S = 0.03


class Port(Protocol):
    """What Monitor needs of a pyserial port (or of a test's fake)."""

    @property
    def in_waiting(self) -> int: ...

    def read(self, size: int = 1) -> bytes: ...

    def write(self, data: bytes, /) -> int | None: ...


class Status(TypedDict):
    """STATUS reply, raw fields (docs/monitor.md)."""

    rec: int
    mode: int
    decim: int
    nch: int
    ch: list[int]
    written: int
    buffered: int
    overflow: int
    state: int
    fault: int
    speed_est: int
    speed_ref: int
    remote: int
    rx_errors: int
    rx_dropped: int


class MonitorError(Exception):
    """Anything that stops a session: a device error reply, a missing or corrupt reply, a port
    that fails. str() is one line for the user."""


def crc16(data: bytes | bytearray, crc: int = 0xFFFF) -> int:
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) if crc & 0x8000 else (crc << 1)
            crc &= 0xFFFF
    return crc


def encode(cmd: int, payload: bytes = b"") -> bytes:
    payload = bytes(payload)
    if len(payload) > MAX_PAYLOAD:
        raise ValueError("payload too long")
    body = bytes([len(payload), cmd]) + payload
    c = crc16(body)
    return bytes([SOF]) + body + bytes([c & 0xFF, c >> 8])


class Decoder:
    """Incremental frame decoder: feed bytes, get (cmd, payload) tuples.
    Bytes that do not form a valid frame are skipped (counted in .bad)."""

    def __init__(self) -> None:
        self.buf = bytearray()
        self.bad = 0

    def feed(self, data: bytes) -> list[tuple[int, bytes]]:
        self.buf += data
        out: list[tuple[int, bytes]] = []
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
    def __init__(self, idx: int, kind: int, fs_milli: int, name: str, unit: str) -> None:
        self.idx, self.kind, self.fs, self.name, self.unit = idx, kind, fs_milli / 1000.0, name, unit

    def to_eng(self, raw: float) -> float:
        return raw / 32768.0 * self.fs if self.kind == KIND_Q15 else float(raw)

    def __repr__(self) -> str:
        return f"{self.name} [{self.unit or '-'}]"


class Param:
    def __init__(self, idx: int, value: int, lo: int, hi: int, name: str) -> None:
        self.idx, self.value, self.min, self.max, self.name = idx, value, lo, hi, name


def max_rate(nch: int, baud: int) -> float:
    """Sample sets per second a stream of nch channels can carry at baud (8N1)."""
    per_frame = (MAX_PAYLOAD - 4) // (2 * nch)
    frame_bytes = 5 + 4 + per_frame * 2 * nch
    return baud / 10.0 / frame_bytes * per_frame


def state_name(state: int) -> str:
    return mc_names.read().state(state)


def _text(raw: bytes, what: str) -> str:
    """A name or unit from the device: printable ASCII, or the reply is corrupt."""
    try:
        s = raw.decode("ascii")
    except UnicodeDecodeError:
        raise MonitorError(f"corrupt {what}: not ASCII text") from None
    if not s.isprintable():
        raise MonitorError(f"corrupt {what}: control characters in it")
    return s


class Monitor:
    """Talks to the device over a pyserial port (or anything with read/write/in_waiting)."""

    def __init__(self, port: Port, timeout: float = 1.0, retries: int = 2) -> None:
        self.port = port
        self.timeout = timeout
        self.retries = retries
        self.dec = Decoder()
        self.data: list[bytes] = []  # DATA frames received while waiting for replies
        self.info: dict[str, int] = {}
        self.vars: list[Var] = []
        self.params: list[Param] = []
        self.nch: int | None = None  # channels of the current selection: DATA frames are checked against it
        self.resends = 0  # requests sent again (a count for the user and the tests)

    # ---- transport ----
    def _read_frames(self) -> list[tuple[int, bytes]]:
        try:
            chunk = self.port.read(self.port.in_waiting or 1)
        except (OSError, ValueError) as e:  # pyserial's SerialException is an OSError
            raise MonitorError(f"reading the port failed: {one_line(e)}") from None
        return self.dec.feed(chunk) if chunk else []

    def _write(self, frame: bytes) -> None:
        try:
            self.port.write(frame)
        except (OSError, ValueError) as e:
            raise MonitorError(f"writing to the port failed: {one_line(e)}") from None

    def _attempt(self, cmd: int, payload: bytes) -> tuple[str, bytes]:
        """One request: ("ok", payload), ("error", [cmd, code]) or ("none", b"")."""
        self._write(encode(cmd, payload))
        t_end = time.monotonic() + self.timeout
        while time.monotonic() < t_end:
            frames = self._read_frames()
            for k, (c, p) in enumerate(frames):
                if c == CMD_DATA:
                    self.data.append(p)
                elif c == (cmd | REPLY) or (c == CMD_ERROR and len(p) == 2 and p[0] in (cmd, 0)):
                    # frames after the reply in the same read are data for later
                    self.data.extend(q for d, q in frames[k + 1 :] if d == CMD_DATA)
                    return ("error", p) if c == CMD_ERROR else ("ok", p)
        return "none", b""

    def request(self, cmd: int, payload: bytes = b"") -> bytes:
        """Sends cmd and returns its reply's payload, checked for its layout's length."""
        why = ""
        for attempt in range(self.retries + 1):
            if attempt > 0:
                self.resends += 1
                time.sleep(RESEND_GAP_S)
            kind, p = self._attempt(cmd, payload)
            if kind == "ok":
                need = REPLY_MIN_LEN.get(cmd, 0)
                if len(p) < need:
                    raise MonitorError(f"command 0x{cmd:02x}: corrupt reply: {len(p)} bytes, its layout has "
                                       f"at least {need} (firmware and tools/scope of different versions?)")
                return p
            if kind == "error":
                code = p[1]
                why = f"error {ERRORS.get(code, str(code))}"
                if code not in TRANSPORT_ERRORS:
                    raise MonitorError(f"command 0x{cmd:02x}: {why}")
                continue  # the request did not get through whole: nothing changed, send again
            why = f"no reply within {self.timeout:g} s"
            if cmd not in IDEMPOTENT:
                break  # it may have been done: sending it again could do it twice
        tries = f" (sent {attempt + 1} times)" if attempt > 0 else ""
        raise MonitorError(f"command 0x{cmd:02x}: {why}{tries}")

    # ---- commands ----
    def connect(self) -> dict[str, int]:
        p = self.request(CMD_INFO)
        ver, nvars, nparams, maxch, bufw, fpwm, maxpl = struct.unpack("<BBBBHIB", p[:11])
        # what the rest of the session divides by or loops over must be plausible
        if not 1 <= maxch <= 16 or not 1 <= fpwm <= 1_000_000 or not 1 <= nvars <= 128 or nparams > 128:
            raise MonitorError(f"corrupt INFO reply: {nvars} variables, {nparams} parameters, {maxch} channels, "
                               f"PWM {fpwm} Hz")
        self.info = {"version": ver, "nvars": nvars, "nparams": nparams, "max_ch": maxch, "buf_words": bufw,
                         "f_pwm": fpwm, "max_payload": maxpl}
        self.vars = []
        for i in range(nvars):
            q = self.request(CMD_VAR_INFO, bytes([i]))
            idx, kind, fs = struct.unpack("<BBi", q[:6])
            if idx != i or kind not in (KIND_Q15, KIND_INT):
                raise MonitorError(f"corrupt VAR_INFO reply for variable {i}: index {idx}, kind {kind}")
            name, nul, unit = q[6:].partition(b"\0")
            if not nul or not name:
                raise MonitorError(f"corrupt VAR_INFO reply for variable {i}: no name")
            self.vars.append(Var(idx, kind, fs, _text(name, f"VAR_INFO {i} name"), _text(unit, f"VAR_INFO {i} unit")))
        self.params = [self.param_info(i) for i in range(nparams)]
        return self.info

    def var(self, name: str) -> Var:
        for v in self.vars:
            if v.name == name:
                return v
        raise MonitorError(f"no variable {name!r}; have {', '.join(v.name for v in self.vars)}")

    def param_info(self, i: int) -> Param:
        q = self.request(CMD_PARAM_INFO, bytes([i]))
        idx, val, lo, hi = struct.unpack("<Bhhh", q[:7])
        if idx != i:
            raise MonitorError(f"corrupt PARAM_INFO reply for parameter {i}: index {idx}")
        return Param(idx, val, lo, hi, _text(q[7:].rstrip(b"\0"), f"PARAM_INFO {i} name"))

    def set_param(self, name: str, value: int) -> None:
        if not -32768 <= value <= 32767:
            raise MonitorError(f"parameter {name}: {value} is outside -32768..32767 (a Q15 mantissa)")
        for p in self.params:
            if p.name == name:
                self.request(CMD_SET_PARAM, struct.pack("<Bh", p.idx, value))
                p.value = value
                return
        raise MonitorError(f"no parameter {name!r}; have {', '.join(p.name for p in self.params)}")

    def select(self, names: list[str], decim: int) -> None:
        if not 1 <= decim <= DECIM_MAX:
            raise MonitorError(f"decimation {decim} is outside 1..{DECIM_MAX}")
        idx = [self.var(n).idx for n in names]
        self.request(CMD_SELECT, struct.pack("<HB", decim, len(idx)) + bytes(idx))
        self.nch = len(idx)

    def start(self, mode: int = MODE_STREAM, trig: int = TRIG_NOW) -> None:
        self.data = []
        self.request(CMD_START, bytes([mode, trig]))

    def stop(self) -> None:
        self.request(CMD_STOP)

    def trigger(self) -> None:
        self.request(CMD_TRIGGER)

    def status(self) -> Status:
        p = self.request(CMD_STATUS)
        f = struct.unpack("<BBHB4BHHBBHhhBHH", p[:26])
        return Status(rec=f[0], mode=f[1], decim=f[2], nch=f[3], ch=list(f[4:8]), written=f[8], buffered=f[9],
                      overflow=f[10], state=f[11], fault=f[12], speed_est=f[13], speed_ref=f[14], remote=f[15],
                      rx_errors=f[16], rx_dropped=f[17])

    def motor(self, action: int) -> None:
        self.request(CMD_MOTOR, bytes([action]))

    def set_speed(self, rpm: float) -> None:
        if not math.isfinite(rpm) or not -32768 <= round(rpm) <= 32767:
            raise MonitorError(f"speed {rpm} rpm is outside the protocol's -32768..32767")
        self.request(CMD_SET_SPEED, struct.pack("<h", round(rpm)))

    def run_motor(self, rpm: float) -> None:
        """Remote speed reference rpm, then START."""
        self.set_speed(rpm)
        self.motor(MOTOR_START)

    # ---- recorded data ----
    def read_data(self, wait: float = 0.0) -> list[tuple[int, int, list[tuple[int, ...]]]]:
        """DATA frames received so far (and during `wait` seconds more), decoded:
        list of (flags, index, [set, ...]) with each set a tuple of raw int16. Frames that
        arrive before any SELECT (an earlier session's) are dropped; a frame that does not
        hold whole sets of the selected channels raises MonitorError."""
        t_end = time.monotonic() + wait
        while True:
            for c, p in self._read_frames():
                if c == CMD_DATA:
                    self.data.append(p)
            if time.monotonic() >= t_end:
                break
        out = []
        frames, self.data = self.data, []
        if self.nch is None:
            return []
        nch = self.nch
        for p in frames:
            if len(p) < 4 or len(p) != 4 + 2 * nch * p[3]:
                raise MonitorError(f"corrupt DATA frame: {len(p)} bytes, not a header and whole sets of "
                                   f"{nch} channels")
            flags, index, nsets = struct.unpack("<BHB", p[:4])
            vals = struct.unpack(f"<{nsets * nch}h", p[4:])
            out.append((flags, index, [vals[i * nch : (i + 1) * nch] for i in range(nsets)]))
        return out


def one_line(e: BaseException) -> str:
    """An exception's text on one line (pyserial's messages can hold a newline)."""
    return " ".join(str(e).split()) or type(e).__name__
