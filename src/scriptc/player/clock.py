"""One show clock: an agreed wall-clock start instant, converted once to the monotonic clock.

Every event is scheduled at `deadline_ns(show_ms)`, an absolute monotonic time, so no
error accumulates from one event to the next. If the host's wall clock is slewed
during a long show (chrony or NTP adjusting it), `follow()` moves the start by at most
`max_slew_ppm` of the elapsed time per call, so the robots follow their synchronised
wall clocks without jumps.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from datetime import datetime, timedelta, timezone

NS = 1_000_000_000
EPOCH = datetime(1970, 1, 1, tzinfo=timezone.utc)


def wall_minus_mono(
    wall: Callable[[], int] = time.time_ns,
    mono: Callable[[], int] = time.monotonic_ns,
    samples: int = 7,
) -> int:
    """Offset of the wall clock from the monotonic clock, from the tightest of a few readings."""
    best: tuple[int, int] | None = None
    for _ in range(samples):
        m1 = mono()
        w = wall()
        m2 = mono()
        if best is None or m2 - m1 < best[0]:
            best = (m2 - m1, w - (m1 + m2) // 2)
    assert best is not None
    return best[1]


class ShowClock:
    """Maps show time (ms from the start cue) to monotonic deadlines (ns) and back."""

    def __init__(
        self,
        start_wall_ns: int,
        *,
        origin_ms: float = 0.0,
        wall: Callable[[], int] = time.time_ns,
        mono: Callable[[], int] = time.monotonic_ns,
        max_slew_ppm: float = 500.0,
    ) -> None:
        self.wall = wall
        self.mono = mono
        self.start_wall_ns = start_wall_ns
        self.origin_ms = origin_ms
        self.offset_ns = wall_minus_mono(wall, mono)
        self.start_mono_ns = start_wall_ns - self.offset_ns
        self.max_slew_ppm = max_slew_ppm
        self._last_follow = mono()
        self.corrected_ns = 0

    def deadline_ns(self, show_ms: float) -> int:
        """Monotonic time at which timeline time `show_ms` happens."""
        return self.start_mono_ns + round((show_ms - self.origin_ms) * 1_000_000)

    def show_ms(self, mono_ns: int | None = None) -> float:
        """Timeline time (ms) at monotonic time `mono_ns` (now by default)."""
        now = self.mono() if mono_ns is None else mono_ns
        return self.origin_ms + (now - self.start_mono_ns) / 1_000_000

    def follow(self) -> int:
        """Move toward the wall clock's current offset by at most the slew cap; return the step."""
        now = self.mono()
        elapsed = max(0, now - self._last_follow)
        self._last_follow = now
        target = self.start_wall_ns - wall_minus_mono(self.wall, self.mono)
        error = target - self.start_mono_ns
        cap = round(elapsed * self.max_slew_ppm / 1e6)
        step = max(-cap, min(cap, error))
        self.start_mono_ns += step
        self.corrected_ns += step
        return step


def parse_instant(text: str) -> int:
    """An ISO-8601 instant (`2026-11-22T20:00:00Z`, or local time without a zone) as Unix ns."""
    cleaned = text.strip().replace("Z", "+00:00").replace("z", "+00:00")
    try:
        dt = datetime.fromisoformat(cleaned)
    except ValueError:
        raise ValueError(
            f"cannot read instant {text!r}: use ISO 8601 like 2026-11-22T20:00:00Z"
        ) from None
    if dt.tzinfo is None:
        dt = dt.astimezone()
    return (dt - EPOCH) // timedelta(microseconds=1) * 1000


def format_instant(ns: int) -> str:
    dt = datetime.fromtimestamp(ns / NS, tz=timezone.utc)
    return dt.isoformat(timespec="milliseconds").replace("+00:00", "Z")
