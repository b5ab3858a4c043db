# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""The X2Cscope services over LNet (docs/x2cscope.md): device info, target state, RAM read and
write, and the scope (load / save parameter 1), as the firmware's target (firmware/x2cscope)
answers them.

Unlike Microchip's clients, every error reply is an error here (TargetError, with the
protocol's code and its name): a refused write never looks like success.

Written from the protocol facts; no code of Microchip's clients is used.
"""

from __future__ import annotations

import contextlib
import struct
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from scope.lnet import Link, LNetError

# Services.
SVC_DEVICE_INFO = 0x00
SVC_GET_STATE = 0x01
SVC_GET_RAM = 0x09
SVC_PUT_RAM = 0x0A
SVC_LOAD_PARAM = 0x11
SVC_SAVE_PARAM = 0x12
SVC_REBOOT = 0x19  # a service this client never sends on its own (the tests do: refused)

PARAM_SCOPE = 1
READ_CHUNK = 253  # a reply is service, error, then at most 253 data bytes
MAX_CHANNELS = 8

# Error ids: the reply's second byte.
ERR_OK = 0x00
ERROR_NAMES = {
    0x13: "checksum",
    0x14: "format",
    0x15: "size",
    0x21: "service",
    0x22: "state",
    0x40: "parameter",
    0x42: "limit",
}
ERROR_TEXT = {
    0x13: "the frame's checksum did not match",
    0x14: "malformed, misaligned or outside the whitelist",
    0x15: "too large for a frame",
    0x21: "no such service",
    0x22: "valid, but not in this state",
    0x40: "no such parameter",
    0x42: "a value outside its range",
}

# Processor ids whose targets use 16-bit addresses (docs/x2cscope.md, "Device info").
PROCESSORS_16BIT: dict[int, str] = {0x8210: "generic dsPIC", 0x8230: "generic PIC24"}
PROCESSORS_16BIT.update(dict.fromkeys(range(0x0221, 0x0229), "dsPIC33FJ"))

# Scope states (load parameter 1).
SCOPE_IDLE = 0
SCOPE_WAIT_TRIG = 1
SCOPE_SAMPLE = 2
SCOPE_POST_TRIG = 7
SCOPE_DELAY = 8
SCOPE_STATE_NAMES = {0: "idle", 1: "waiting for the trigger", 2: "sampling", 7: "after the trigger",
                     8: "trigger delay"}
DSP_STATE_NAMES = {0x04: "application running, outputs off", 0x05: "application running, outputs on"}

TRIG_NEW = 0x80
TRIG_FLOAT = 0x40
TRIG_SIGNED = 0x20


class X2CError(LNetError):
    """A service failed (one-line message)."""


class TargetError(X2CError):
    """The target answered with an error code."""

    def __init__(self, service: int, code: int, what: str = "") -> None:
        self.service = service
        self.code = code
        self.what = what
        super().__init__(f"{what + ': ' if what else ''}the target refused service 0x{service:02X} with error "
                         f"0x{code:02X} ({self.name}: {ERROR_TEXT.get(code, 'an unknown code')})")

    @property
    def name(self) -> str:
        return ERROR_NAMES.get(self.code, "unknown")


@dataclass(frozen=True)
class DeviceInfo:
    monitor_version: int
    app_version: int
    max_frame: int
    processor_id: int
    monitor_date: str
    monitor_time: str
    app_date: str
    app_time: str
    dsp_state: int
    event_type: int
    event_id: int
    table_address: int

    @property
    def processor(self) -> str:
        return PROCESSORS_16BIT.get(self.processor_id, "unknown")


def parse_device_info(r: bytes) -> DeviceInfo:
    if len(r) != 44:
        raise X2CError(f"device info: {len(r)} bytes, want 44")

    def text(a: int, b: int) -> str:
        return r[a:b].decode("ascii", "replace")

    mon, app, maxf, pid = struct.unpack_from("<HHBH", r, 0)
    dsp, ev_type, ev_id, table = struct.unpack_from("<BHII", r, 33)
    return DeviceInfo(mon, app, maxf, pid, text(7, 16), text(16, 20), text(20, 29), text(29, 33), dsp, ev_type,
                      ev_id, table)


@dataclass(frozen=True)
class ScopeState:
    """Load parameter 1: the scope as the target has it (29 bytes)."""

    state: int
    channels: int
    prescaler: int
    pointer: int  # the next byte to write
    buffer_address: int
    trigger_delay: int  # bytes; > 0 history, < 0 wait
    trigger_position: int  # bytes: where the dataset at or after the edge is
    used_length: int  # bytes of whole datasets
    buffer_size: int
    version: int

    FORMAT = "<BBHIIiiIIB"

    @classmethod
    def parse(cls, r: bytes) -> ScopeState:
        if len(r) != struct.calcsize(cls.FORMAT):
            raise X2CError(f"scope state: {len(r)} bytes, want {struct.calcsize(cls.FORMAT)}")
        return cls(*struct.unpack(cls.FORMAT, r))

    @property
    def done(self) -> bool:
        return self.state == SCOPE_IDLE or self.pointer == self.used_length

    @property
    def state_name(self) -> str:
        return SCOPE_STATE_NAMES.get(self.state, f"state {self.state}")


# ---- the scope's configuration ---------------------------------------------------------------

KINDS = ("S", "U", "B", "F")  # signed, unsigned, bool, IEEE float


@dataclass(frozen=True)
class Channel:
    address: int
    size: int  # 1, 2 or 4 bytes
    kind: str = "U"  # how the bytes read (not sent)
    source_type: int = 0  # 0: an absolute address

    def decode(self, b: bytes) -> int | float:
        if self.kind == "F":
            return float(struct.unpack("<f", b)[0])
        return int.from_bytes(b, "little", signed=self.kind == "S")


@dataclass(frozen=True)
class Trigger:
    """An edge on a variable (or auto). level is the raw value (a float for a float source);
    delay is in datasets: > 0 keeps that many before the edge, < 0 waits that many after it."""

    address: int = 0
    size: int = 2
    kind: str = "S"
    level: int | float = 0
    delay: int = 0
    rising: bool = True
    auto: bool = False  # trigger mode 0: fires at once
    source_type: int = 0

    @property
    def dtype(self) -> int:
        d = TRIG_NEW | (self.size & 0x0F)
        if self.kind == "F":
            d |= TRIG_FLOAT
        if self.kind in ("S", "F"):
            d |= TRIG_SIGNED
        return d

    def level_bytes(self) -> bytes:
        if self.kind == "F":
            return struct.pack("<f", float(self.level))
        if isinstance(self.level, float) and not self.level.is_integer():
            raise X2CError(f"trigger level {self.level}: an integer source wants a whole number")
        try:
            return int(self.level).to_bytes(self.size, "little", signed=self.kind == "S")
        except OverflowError:
            raise X2CError(f"trigger level {self.level} does not fit the source's {self.size} byte(s)") from None


@dataclass(frozen=True)
class ScopeConfig:
    channels: tuple[Channel, ...]
    prescaler: int = 0  # one dataset every prescaler + 1 calls
    trigger: Trigger | None = None  # None: sample until full (state 2)

    @property
    def dataset_size(self) -> int:
        return sum(c.size for c in self.channels)

    @property
    def state(self) -> int:
        return SCOPE_SAMPLE if self.trigger is None else SCOPE_WAIT_TRIG

    def encode(self) -> bytes:
        """The data of save parameter 1 after its id: state, channels, prescaler, the channels,
        the trigger."""
        if not 0 <= self.prescaler <= 0xFFFF:
            raise X2CError(f"prescaler {self.prescaler}: want 0..65535")
        out = bytearray(struct.pack("<BBH", self.state, len(self.channels), self.prescaler))
        for c in self.channels:
            out += struct.pack("<BIB", c.source_type, c.address, c.size)
        t = self.trigger
        if t is None:
            # no trigger: a 2-byte level of 0 from address 0, as the other clients send it
            out += struct.pack("<BBI", TRIG_NEW | 2, 0, 0) + bytes(2) + struct.pack("<iBB", 0, 1, 0)
        else:
            delay_bytes = t.delay * self.dataset_size
            out += struct.pack("<BBI", t.dtype, t.source_type, t.address) + t.level_bytes()
            out += struct.pack("<iBB", delay_bytes, 1 if t.rising else 0, 0 if t.auto else 1)
        return bytes(out)


@dataclass
class Capture:
    """One capture: the datasets in time order, rotated as a client does."""

    config: ScopeConfig
    state: ScopeState
    raw: bytes  # the buffer as read (used_length bytes)
    shift: int  # datasets the buffer was rotated by
    datasets: list[bytes] = field(default_factory=list)

    @property
    def trigger_index(self) -> int | None:
        """The index of the dataset stored at or after the edge (delay >= 0), else None."""
        t = self.config.trigger
        return t.delay if t is not None and t.delay >= 0 else None

    def channel(self, k: int) -> list[int | float]:
        """Channel k's values in time order."""
        ch = self.config.channels
        at = sum(c.size for c in ch[:k])
        return [ch[k].decode(d[at:at + ch[k].size]) for d in self.datasets]


def split_and_rotate(cfg: ScopeConfig, st: ScopeState, raw: bytes) -> Capture:
    """The buffer as whole datasets in time order. With a trigger and a delay >= 0 the ring is
    rotated so that it starts trigger_position / dataset - delay datasets in (the oldest kept);
    a negative delay records from the start of the buffer: no rotation."""
    ds = cfg.dataset_size
    if ds <= 0:
        raise X2CError("a capture needs at least one channel")
    sets = [raw[i:i + ds] for i in range(0, len(raw) - len(raw) % ds, ds)]
    shift = 0
    if cfg.trigger is not None and cfg.trigger.delay >= 0 and sets:
        shift = (st.trigger_position // ds - cfg.trigger.delay) % len(sets)
        sets = sets[shift:] + sets[:shift]
    return Capture(cfg, st, raw, shift, sets)


Progress = Callable[[ScopeState, float], None]


class Target:
    """The services of one X2Cscope target over a Link."""

    def __init__(self, link: Link) -> None:
        self.link = link
        self.info: DeviceInfo | None = None
        self.address_bytes = 2

    def call(self, service: int, payload: bytes = b"", what: str = "") -> bytes:
        """One service; its reply data after the error byte. TargetError for an error reply."""
        r = self.link.request(bytes((service,)) + payload)
        if r[1] != ERR_OK:
            raise TargetError(service, r[1], what)
        return r[2:]

    # ---- device ----

    def device_info(self) -> DeviceInfo:
        info = parse_device_info(self.call(SVC_DEVICE_INFO, what="device info"))
        if info.processor_id not in PROCESSORS_16BIT:
            known = ", ".join(f"0x{k:04X}" for k in sorted(PROCESSORS_16BIT))
            raise X2CError(f"device info: processor id 0x{info.processor_id:04X} is unknown to this client, so "
                           f"it cannot tell the target's address width (it knows {known}: 16-bit addresses)")
        self.info = info
        self.address_bytes = 2
        return info

    connect = device_info

    def target_state(self) -> int:
        r = self.call(SVC_GET_STATE, what="target state")
        if len(r) != 1:
            raise X2CError(f"target state: {len(r)} bytes, want 1")
        return r[0]

    # ---- RAM ----

    def _address(self, addr: int, n: int) -> bytes:
        top = 1 << (8 * self.address_bytes)
        if addr < 0 or addr + max(n, 1) > top:
            raise X2CError(f"address 0x{addr:X} (+{n}) is outside the target's {8 * self.address_bytes}-bit space")
        return addr.to_bytes(self.address_bytes, "little")

    def read_once(self, addr: int, n: int, width: int = 1) -> bytes:
        """One read request of n bytes (n <= 255 as sent; the target refuses what does not fit)."""
        if not 0 <= n <= 0xFF:
            raise X2CError(f"read of {n} bytes: one request counts 0..255")
        r = self.call(SVC_GET_RAM, self._address(addr, n) + bytes((n, width)), f"read 0x{addr:04X} ({n} bytes)")
        if len(r) != n:
            raise X2CError(f"read 0x{addr:04X}: {len(r)} bytes back, asked for {n}")
        return r

    def read(self, addr: int, n: int, width: int = 1) -> bytes:
        """n bytes at addr, accessed width bytes at a time, in requests of at most 253 bytes."""
        chunk = READ_CHUNK - READ_CHUNK % max(1, width)
        out = bytearray()
        while len(out) < n:
            k = min(chunk, n - len(out))
            out += self.read_once(addr + len(out), k, width)
        return bytes(out)

    def write(self, addr: int, width: int, data: bytes) -> None:
        """Writes data at addr, width bytes at a time. TargetError when refused."""
        if not 1 <= len(data) <= 255 - 4:
            raise X2CError(f"write of {len(data)} bytes: one request carries 1..251")
        self.call(SVC_PUT_RAM, self._address(addr, len(data)) + bytes((width,)) + data,
                  f"write 0x{addr:04X} ({len(data)} bytes)")

    # ---- scope ----

    def scope_state(self) -> ScopeState:
        return ScopeState.parse(self.call(SVC_LOAD_PARAM, struct.pack("<H", PARAM_SCOPE), "scope state"))

    def scope_save_raw(self, config: bytes, param: int = PARAM_SCOPE) -> None:
        self.call(SVC_SAVE_PARAM, struct.pack("<H", param) + config, "scope configuration")

    def scope_save(self, cfg: ScopeConfig) -> None:
        self.scope_save_raw(cfg.encode())

    def scope_stop(self) -> None:
        self.scope_save_raw(struct.pack("<BBH", SCOPE_IDLE, 0, 0))

    def capture(self, cfg: ScopeConfig, timeout: float = 10.0, progress: Progress | None = None,
                poll_s: float = 0.02, after_start: Callable[[], None] | None = None) -> Capture:
        """Configures and starts the scope, waits until it is done, reads the buffer in 253-byte
        chunks and returns the datasets in time order. after_start runs once the scope is
        started (what should trigger it, say)."""
        if not 1 <= len(cfg.channels) <= MAX_CHANNELS:
            raise X2CError(f"a capture takes 1..{MAX_CHANNELS} channels, not {len(cfg.channels)}")
        self.scope_save(cfg)
        if after_start is not None:
            after_start()
        t0 = time.monotonic()
        while True:
            st = self.scope_state()
            if progress is not None:
                progress(st, time.monotonic() - t0)
            if st.done:
                break
            if time.monotonic() - t0 > timeout:
                with contextlib.suppress(LNetError):  # the timeout is the error to report
                    self.scope_stop()
                raise X2CError(f"capture: not done within {timeout:g} s (the scope was {st.state_name}); "
                               "stopped it")
            time.sleep(poll_s)
        if st.used_length > st.buffer_size:
            raise X2CError(f"scope state: used length {st.used_length} exceeds the buffer's {st.buffer_size} bytes")
        raw = self.read(st.buffer_address, st.used_length, 1)
        return split_and_rotate(cfg, st, raw)
