# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""LNet, the frame layer X2Cscope speaks (docs/x2cscope.md, "Frame"), and its transports.

    SYN 0x55 | SIZE | NODE | DATA[SIZE] | CRC

CRC = (SYN + SIZE + NODE + DATA) mod 256 over the values before escaping, sent inverted
(0xAA, 0xFD) when it equals one of the reserved bytes 0x55 and 0x02. Wherever SIZE, NODE or a
DATA byte is reserved, a 0x00 fill byte follows it; fills are neither counted nor summed. A 0x55
followed by anything but the fill is a new SYN (how a receiver finds its place again).

Written from the protocol facts; no code of Microchip's clients is used.

Transports (open_transport): a pseudo-terminal through os + termios (raw, 8N1; no pyserial
needed), a serial port through pyserial when it is installed (else termios too), whatever else
pyserial opens (COM3, its URLs), and TCP ("tcp://HOST:PORT").
"""

from __future__ import annotations

import contextlib
import errno
import importlib.util
import os
import re
import select
import socket
import stat
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any, Protocol

SYN = 0x55
FILL = 0x00
RESERVED = (0x55, 0x02)
NODE = 1  # the client sends node 1; the target answers with its own id, 1
MAX_DATA = 255
DEFAULT_TIMEOUT_S = 1.0
DEFAULT_TCP_PORT = 12666


class LNetError(Exception):
    """A link failure: no reply, a corrupt one, one for another request, a port that fails.
    The message is one line."""


# ---- frames ---------------------------------------------------------------------------------


def crc_raw(size: int, node: int, data: bytes) -> int:
    """The sum before the inversion rule."""
    return (SYN + size + node + sum(data)) & 0xFF


def crc(size: int, node: int, data: bytes) -> int:
    """The checksum byte as sent: the sum, inverted when it is reserved."""
    s = crc_raw(size, node, data)
    return (~s & 0xFF) if s in RESERVED else s


def _escaped(b: int) -> bytes:
    return bytes((b, FILL)) if b in RESERVED else bytes((b,))


def encode(data: bytes, node: int = NODE) -> bytes:
    """One frame on the wire."""
    if not 1 <= len(data) <= MAX_DATA:
        raise ValueError(f"LNet frames carry 1..{MAX_DATA} data bytes, not {len(data)}")
    if not 0 <= node <= 0xFF:
        raise ValueError(f"node {node} is not a byte")
    out = bytearray((SYN,))
    out += _escaped(len(data))
    out += _escaped(node)
    for b in data:
        out += _escaped(b)
    out.append(crc(len(data), node, data))
    return bytes(out)


@dataclass(frozen=True)
class Frame:
    node: int
    data: bytes
    crc_inverted: bool  # the sender inverted the checksum (its sum was 0x55 or 0x02)


@dataclass(frozen=True)
class BadFrame:
    why: str  # "checksum", or "fill" (a 0x02 without its fill)
    data: bytes  # what was received of the data


_HUNT, _SIZE, _NODE, _DATA, _CRC = range(5)


class Decoder:
    """A streaming receiver: feed() bytes as they come, get whole frames and bad ones back."""

    def __init__(self) -> None:
        self.state = _HUNT
        self.size = 0
        self.node = 0
        self.data = bytearray()
        self.fill_after = -1  # the reserved byte just taken, whose fill must follow; -1: none

    def _start(self) -> None:
        self.state = _SIZE
        self.data = bytearray()
        self.fill_after = -1

    def _take(self, b: int) -> None:
        """Takes one unescaped value of SIZE, NODE or DATA."""
        if self.state == _SIZE:
            if b == 0:
                self.state = _HUNT  # 0x55 0x00 outside a frame: a data byte, not a SYN
                return
            self.size = b
            self.state = _NODE
        elif self.state == _NODE:
            self.node = b
            self.state = _DATA
        else:
            self.data.append(b)
        if self.state == _DATA and len(self.data) == self.size:
            self.state = _CRC

    def feed(self, chunk: bytes) -> list[Frame | BadFrame]:
        out: list[Frame | BadFrame] = []
        for b in chunk:
            self._byte(b, out)
        return out

    def _byte(self, b: int, out: list[Frame | BadFrame]) -> None:
        if self.fill_after >= 0:
            reserved, self.fill_after = self.fill_after, -1
            if b == FILL:
                return  # the fill: the reserved value was data
            if reserved == SYN:
                # the 0x55 was a SYN: this byte is a new frame's SIZE
                self._start()
                self._take(b)
                self._after_take(b)
                return
            out.append(BadFrame("fill", bytes(self.data)))  # a 0x02 without its fill
            self.state = _HUNT
            # this byte may start the next frame
        if self.state == _HUNT:
            if b == SYN:
                self._start()
            return
        if self.state == _CRC:
            if b == SYN:  # a checksum is never 0x55: the frame was cut, this is a new SYN
                out.append(BadFrame("checksum", bytes(self.data)))
                self._start()
                return
            want = crc(self.size, self.node, bytes(self.data))
            if b == want:
                out.append(Frame(self.node, bytes(self.data), crc_raw(self.size, self.node, bytes(self.data))
                                 in RESERVED))
            else:
                out.append(BadFrame("checksum", bytes(self.data)))
            self.state = _HUNT
            return
        self._take(b)
        self._after_take(b)

    def _after_take(self, b: int) -> None:
        if b in RESERVED and self.state != _HUNT:
            self.fill_after = b


# ---- transports -----------------------------------------------------------------------------


class Transport(Protocol):
    def write(self, data: bytes) -> None: ...

    def read(self, timeout: float) -> bytes:
        """What arrives within timeout (b"" if nothing)."""
        ...

    def drain(self) -> None:
        """Drops what was received and not read."""
        ...

    def close(self) -> None: ...


def _baud_constant(baud: int) -> int:
    import termios

    c = getattr(termios, f"B{baud}", None)
    if not isinstance(c, int):
        raise LNetError(f"{baud} Bd is not a rate this system's termios knows")
    return c


class TtyTransport:
    """A tty or pty path, raw 8N1 at the given rate, through os and termios only."""

    def __init__(self, path: str, baud: int = 115200) -> None:
        import termios

        speed = _baud_constant(baud)
        try:
            fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        except OSError as e:
            raise LNetError(f"cannot open port {path!r}: {e.strerror or e}") from None
        try:
            if not os.isatty(fd):
                raise LNetError(f"port {path!r} is not a terminal (a serial port or a pty)")
            a = termios.tcgetattr(fd)
            a[0] &= ~(termios.IGNBRK | termios.BRKINT | termios.PARMRK | termios.ISTRIP | termios.INLCR
                      | termios.IGNCR | termios.ICRNL | termios.IXON | termios.IXOFF | termios.IXANY
                      | termios.INPCK)
            a[1] &= ~termios.OPOST
            a[2] &= ~(termios.CSIZE | termios.PARENB | termios.CSTOPB | getattr(termios, "CRTSCTS", 0))
            a[2] |= termios.CS8 | termios.CREAD | termios.CLOCAL
            a[3] &= ~(termios.ECHO | termios.ECHONL | termios.ICANON | termios.ISIG | termios.IEXTEN)
            a[4] = a[5] = speed
            a[6][termios.VMIN] = 0
            a[6][termios.VTIME] = 0
            termios.tcsetattr(fd, termios.TCSANOW, a)
        except LNetError:
            os.close(fd)
            raise
        except (OSError, termios.error) as e:
            os.close(fd)
            raise LNetError(f"cannot set up port {path!r}: {_one_line(e)}") from None
        self.fd = fd
        self.path = path

    def write(self, data: bytes) -> None:
        view = memoryview(data)
        t_end = time.monotonic() + 2.0
        while view:
            try:
                n = os.write(self.fd, view)
                view = view[n:]
            except BlockingIOError:
                if time.monotonic() > t_end:
                    raise LNetError(f"port {self.path!r}: nobody takes the bytes written") from None
                select.select([], [self.fd], [], 0.05)
            except OSError as e:
                raise LNetError(f"port {self.path!r}: write failed: {e.strerror or e}") from None

    def read(self, timeout: float) -> bytes:
        try:
            r, _, _ = select.select([self.fd], [], [], max(0.0, timeout))
            if not r:
                return b""
            return os.read(self.fd, 4096)
        except BlockingIOError:
            return b""
        except OSError as e:
            if e.errno == errno.EIO:
                raise LNetError(f"port {self.path!r}: the other side closed it") from None
            raise LNetError(f"port {self.path!r}: read failed: {e.strerror or e}") from None

    def drain(self) -> None:
        while self.read(0.0):
            pass

    def close(self) -> None:
        with contextlib.suppress(OSError):
            os.close(self.fd)


class SerialTransport:
    """pyserial's port (8N1): COM ports, pyserial URLs, any device pyserial opens."""

    def __init__(self, path: str, baud: int = 115200) -> None:
        try:
            import serial
        except ImportError:
            raise LNetError(f"port {path!r} needs pyserial, which is not installed (run tools/bootstrap)") from None
        try:
            self.port: Any = serial.serial_for_url(path, baudrate=baud, bytesize=8, parity="N", stopbits=1,
                                                   timeout=0, write_timeout=2.0)
        except (OSError, ValueError) as e:  # SerialException is an OSError
            raise LNetError(f"cannot open port {path!r}: {_one_line(e)}") from None
        self.path = path

    def write(self, data: bytes) -> None:
        try:
            self.port.write(data)
            self.port.flush()
        except (OSError, ValueError) as e:
            raise LNetError(f"port {self.path!r}: write failed: {_one_line(e)}") from None

    def read(self, timeout: float) -> bytes:
        try:
            self.port.timeout = max(0.0, timeout)
            first = bytes(self.port.read(1))
            if not first:
                return b""
            self.port.timeout = 0
            return first + bytes(self.port.read(4096))
        except (OSError, ValueError) as e:
            raise LNetError(f"port {self.path!r}: read failed: {_one_line(e)}") from None

    def drain(self) -> None:
        with contextlib.suppress(OSError, ValueError):
            self.port.reset_input_buffer()

    def close(self) -> None:
        with contextlib.suppress(OSError, ValueError):
            self.port.close()


class TcpTransport:
    """The same frames over TCP."""

    def __init__(self, host: str, port: int, timeout: float = 3.0) -> None:
        try:
            self.sock = socket.create_connection((host, port), timeout=timeout)
        except OSError as e:
            raise LNetError(f"cannot connect to {host}:{port}: {e.strerror or _one_line(e)}") from None
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.where = f"{host}:{port}"

    def write(self, data: bytes) -> None:
        try:
            self.sock.settimeout(2.0)
            self.sock.sendall(data)
        except OSError as e:
            raise LNetError(f"tcp {self.where}: send failed: {e.strerror or _one_line(e)}") from None

    def read(self, timeout: float) -> bytes:
        try:
            r, _, _ = select.select([self.sock], [], [], max(0.0, timeout))
            if not r:
                return b""
            self.sock.settimeout(0.0)
            got = self.sock.recv(4096)
        except BlockingIOError:
            return b""
        except OSError as e:
            raise LNetError(f"tcp {self.where}: receive failed: {e.strerror or _one_line(e)}") from None
        if not got:
            raise LNetError(f"tcp {self.where}: the target closed the connection")
        return got

    def drain(self) -> None:
        while self.read(0.0):
            pass

    def close(self) -> None:
        with contextlib.suppress(OSError):
            self.sock.close()


def parse_tcp(spec: str) -> tuple[str, int]:
    """tcp://HOST[:PORT] -> (host, port); the port defaults to X2Cscope's 12666."""
    rest = spec[len("tcp://"):]
    host, colon, port_s = rest.rpartition(":")
    if not colon:
        host, port_s = rest, str(DEFAULT_TCP_PORT)
    host = host.strip("[]")
    if not host or not port_s.isdigit() or not 1 <= int(port_s) <= 65535:
        raise LNetError(f"port {spec!r}: want tcp://HOST:PORT")
    return host, int(port_s)


def _is_pty(path: str) -> bool:
    """A pseudo-terminal's slave side (Linux, the BSDs and macOS name them so)."""
    real = os.path.realpath(path)
    return real.startswith("/dev/pts/") or re.fullmatch(r"/dev/tty[p-za-e][0-9a-f]", real) is not None


def _have_pyserial() -> bool:
    return importlib.util.find_spec("serial") is not None


def open_transport(port: str, baud: int = 115200, kind: str = "auto") -> Transport:
    """The transport for a port name:
    tcp://HOST[:PORT]                 TCP;
    a pseudo-terminal (/dev/pts/N)    os + termios, raw 8N1 (pyserial never needed);
    any other terminal device         pyserial when installed, else os + termios;
    anything else (COM3, a URL)       pyserial.
    kind "tty" or "serial" forces one of the two for a device path."""
    if port.startswith("tcp://"):
        host, p = parse_tcp(port)
        return TcpTransport(host, p)
    if kind == "serial" or (os.name != "posix" and kind != "tty"):
        return SerialTransport(port, baud)
    try:
        st = os.stat(port)
    except OSError as e:
        if kind != "tty" and "://" in port:
            return SerialTransport(port, baud)  # a pyserial URL
        raise LNetError(f"cannot open port {port!r}: {e.strerror or e}") from None
    if not stat.S_ISCHR(st.st_mode):
        raise LNetError(f"port {port!r} is not a terminal device (a serial port or a pty)")
    if kind == "auto" and not _is_pty(port) and _have_pyserial():
        return SerialTransport(port, baud)
    return TtyTransport(port, baud)


def _one_line(e: BaseException) -> str:
    return " ".join(str(e).split()) or type(e).__name__


# ---- request and response ----------------------------------------------------------------


@dataclass
class LinkStats:
    """What went over the link, for the tests' escaping checks."""

    frames_sent: int = 0
    frames_received: int = 0
    crc_inverted_sent: int = 0
    crc_inverted_received: int = 0
    fills_sent: int = 0
    fills_received: int = 0
    bytes_sent: int = 0
    bytes_received: int = 0
    seen: list[bytes] = field(default_factory=list)  # raw received chunks, when kept


class Link:
    """Strict request / response over one transport."""

    def __init__(self, transport: Transport, timeout: float = DEFAULT_TIMEOUT_S, keep_raw: bool = False) -> None:
        self.transport = transport
        self.timeout = timeout
        self.decoder = Decoder()
        self.stats = LinkStats()
        self.keep_raw = keep_raw

    def send_raw(self, wire: bytes) -> None:
        """Bytes as they are (tests: corrupt frames)."""
        self.transport.write(wire)
        self.stats.bytes_sent += len(wire)

    def _count_sent(self, wire: bytes, data: bytes) -> None:
        self.stats.frames_sent += 1
        self.stats.fills_sent += len(wire) - len(data) - 4
        if crc_raw(len(data), NODE, data) in RESERVED:
            self.stats.crc_inverted_sent += 1

    def receive(self, timeout: float | None = None) -> Frame | BadFrame | None:
        """The next frame (or bad one) within timeout; None when nothing came."""
        t_end = time.monotonic() + (self.timeout if timeout is None else timeout)
        while True:
            left = t_end - time.monotonic()
            got = self.transport.read(max(0.0, min(left, 0.05)))
            if got:
                self.stats.bytes_received += len(got)
                if self.keep_raw:
                    self.stats.seen.append(got)
                for ev in self.decoder.feed(got):
                    if isinstance(ev, Frame):
                        self.stats.frames_received += 1
                        self.stats.crc_inverted_received += int(ev.crc_inverted)
                        self.stats.fills_received += sum(1 for b in (ev.data + bytes((len(ev.data), ev.node)))
                                                         if b in RESERVED)
                    return ev  # a reply is one frame: the rest of a chunk would be noise
            elif left <= 0:
                return None

    def request(self, data: bytes) -> bytes:
        """Sends one request (service, service data...) and returns the reply's data (service, error,
        data...). Raises LNetError for no reply, a bad checksum, another node or another service."""
        wire = encode(data)
        self.transport.drain()
        self.decoder = Decoder()
        self.send_raw(wire)
        self._count_sent(wire, data)
        ev = self.receive()
        if ev is None:
            raise LNetError(f"no reply to service 0x{data[0]:02X} within {self.timeout:g} s")
        if isinstance(ev, BadFrame):
            what = "a bad checksum" if ev.why == "checksum" else "a reserved byte without its fill"
            raise LNetError(f"the reply to service 0x{data[0]:02X} has {what}")
        if ev.node != NODE:
            raise LNetError(f"a reply from node {ev.node}, not {NODE}")
        if len(ev.data) < 2:
            raise LNetError(f"a reply of {len(ev.data)} byte(s): want at least service and error")
        if ev.data[0] == 0 and ev.data[1] != 0:
            return ev.data  # a frame-level refusal (0x15, too large for the target) comes under service 0
        if ev.data[0] != data[0]:
            raise LNetError(f"a reply for service 0x{ev.data[0]:02X} (error 0x{ev.data[1]:02X}) to a request "
                            f"for service 0x{data[0]:02X}")
        return ev.data

    def close(self) -> None:
        self.transport.close()


@contextlib.contextmanager
def opened(port: str, baud: int = 115200, timeout: float = DEFAULT_TIMEOUT_S, kind: str = "auto") -> Iterator[Link]:
    link = Link(open_transport(port, baud, kind), timeout)
    try:
        yield link
    finally:
        link.close()
