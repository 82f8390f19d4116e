"""Check this host's clock against an NTP server or a peer, before the show.

Hosts keep time with chrony, NTP or PTP; scriptc only measures how far off this host
is and refuses to start past a bound. `offset` is an SNTP (RFC 4330) query: offset =
((t2 - t1) + (t3 - t4)) / 2 over a few exchanges, keeping the one with the smallest
round trip. `serve` answers SNTP queries from this host's clock, so one robot (or the
show controller) can be the peer the others check against.
"""

from __future__ import annotations

import socket
import struct
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

NTP_EPOCH_OFFSET = 2_208_988_800  # seconds from 1900 to 1970
PACKET = struct.Struct("!B B b b 11I")


class TimeSyncError(Exception):
    pass


def _to_ntp(ns: int) -> tuple[int, int]:
    seconds, rem = divmod(ns, 1_000_000_000)
    return seconds + NTP_EPOCH_OFFSET, (rem << 32) // 1_000_000_000


def _from_ntp(seconds: int, fraction: int) -> int:
    return (seconds - NTP_EPOCH_OFFSET) * 1_000_000_000 + (fraction * 1_000_000_000 >> 32)


@dataclass(frozen=True, slots=True)
class Measurement:
    offset_ms: float  # how far the server's clock is ahead of ours
    delay_ms: float  # round trip
    server: str


def _split(server: str, default_port: int = 123) -> tuple[str, int]:
    host, _, port = server.rpartition(":") if server.count(":") == 1 else (server, "", "")
    return (host or server), int(port) if port else default_port


def offset(
    server: str, *, samples: int = 4, timeout: float = 1.0, wall: Callable[[], int] = time.time_ns
) -> Measurement:
    """Measure this host's offset from `server` (`host` or `host:port`)."""
    host, port = _split(server)
    best: Measurement | None = None
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        sock.settimeout(timeout)
        for _ in range(samples):
            t1 = wall()
            sec, frac = _to_ntp(t1)
            request = PACKET.pack(0x23, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, sec, frac)  # v4, client
            try:
                sock.sendto(request, (host, port))
                data, _ = sock.recvfrom(512)
            except (TimeoutError, OSError) as exc:
                if best is None and _ == samples - 1:
                    raise TimeSyncError(f"no answer from time server {server}: {exc}") from None
                continue
            t4 = wall()
            if len(data) < PACKET.size:
                continue
            fields = PACKET.unpack(data[: PACKET.size])
            if fields[1] == 0 or (fields[0] & 0x07) not in (4, 5):
                continue  # kiss-of-death or not a server reply
            t2 = _from_ntp(fields[11], fields[12])  # server receive
            t3 = _from_ntp(fields[13], fields[14])  # server transmit
            m = Measurement(((t2 - t1) + (t3 - t4)) / 2e6, ((t4 - t1) - (t3 - t2)) / 1e6, server)
            if best is None or m.delay_ms < best.delay_ms:
                best = m
    if best is None:
        raise TimeSyncError(f"no valid answer from time server {server}")
    return best


def serve(
    port: int,
    *,
    host: str = "0.0.0.0",
    stop: threading.Event | None = None,
    wall: Callable[[], int] = time.time_ns,
    ready: Callable[[int], None] | None = None,
) -> None:
    """Answer SNTP queries from this host's clock until `stop` is set."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        sock.bind((host, port))
        sock.settimeout(0.2)
        if ready:
            ready(sock.getsockname()[1])
        while stop is None or not stop.is_set():
            try:
                data, addr = sock.recvfrom(512)
            except TimeoutError:
                continue
            t2 = wall()
            if len(data) < PACKET.size:
                continue
            request = PACKET.unpack(data[: PACKET.size])
            t3 = wall()
            reply = PACKET.pack(
                0x24,
                2,
                0,
                -20,
                0,
                0,
                0x7F000001,
                *_to_ntp(t3),
                request[13],
                request[14],
                *_to_ntp(t2),
                *_to_ntp(t3),
            )
            sock.sendto(reply, addr)
