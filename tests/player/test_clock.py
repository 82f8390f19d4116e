"""The show clock and the deadline scheduler, with injected clocks where timing is not the point."""

from __future__ import annotations

import threading
import time

import pytest

from scriptc.player.clock import ShowClock, format_instant, parse_instant, wall_minus_mono
from scriptc.player.scheduler import Event, Scheduler, wait_until


class FakeClocks:
    def __init__(self) -> None:
        self.mono_ns = 5_000_000_000
        self.wall_offset = 1_700_000_000_000_000_000

    def mono(self) -> int:
        return self.mono_ns

    def wall(self) -> int:
        return self.mono_ns + self.wall_offset


def test_deadlines_are_absolute_from_the_start_instant() -> None:
    c = FakeClocks()
    start = c.wall() + 2_000_000_000
    clock = ShowClock(start, wall=c.wall, mono=c.mono)
    assert clock.deadline_ns(0) == c.mono_ns + 2_000_000_000
    assert clock.deadline_ns(1500) - clock.deadline_ns(0) == 1_500_000_000
    assert clock.show_ms(c.mono_ns + 2_250_000_000) == 250.0


def test_rehearsal_origin_shifts_the_timeline() -> None:
    c = FakeClocks()
    clock = ShowClock(c.wall(), origin_ms=22_290, wall=c.wall, mono=c.mono)
    assert clock.deadline_ns(22_290) == c.mono_ns
    assert clock.show_ms(c.mono_ns + 10_000_000) == 22_300.0


def test_a_slewed_wall_clock_is_followed_with_a_capped_correction() -> None:
    c = FakeClocks()
    clock = ShowClock(c.wall() + 10**9, wall=c.wall, mono=c.mono, max_slew_ppm=500)
    before = clock.deadline_ns(60_000)
    c.wall_offset += 3_000_000  # NTP stepped the wall clock 3 ms ahead
    c.mono_ns += 1_000_000_000  # one second later
    step = clock.follow()
    assert step == -500_000  # at most 500 ppm of one second
    for _ in range(10):
        c.mono_ns += 1_000_000_000
        clock.follow()
    assert clock.deadline_ns(60_000) == before - 3_000_000  # converged, never jumped


def test_iso_instants() -> None:
    ns = parse_instant("2026-11-22T20:00:00.250Z")
    assert ns == 1_795_377_600_250_000_000
    assert format_instant(ns) == "2026-11-22T20:00:00.250Z"
    assert parse_instant("2026-11-22T21:00:00.250+01:00") == ns
    with pytest.raises(ValueError, match="ISO 8601"):
        parse_instant("tomorrow at eight")


def test_offset_reading_is_consistent() -> None:
    a = wall_minus_mono()
    b = wall_minus_mono()
    assert abs(a - b) < 5_000_000


def test_scheduler_runs_events_in_order_at_their_deadlines() -> None:
    clock = ShowClock(time.time_ns() + 50_000_000)
    done: list[tuple[str, float]] = []
    events = [
        Event(t, i, "x", lambda t=t: done.append((f"e{t}", clock.show_ms())))
        for i, t in enumerate([120, 0, 60, 30, 90])
    ]
    Scheduler(clock).run(events)
    assert [name for name, _ in done] == ["e0", "e30", "e60", "e90", "e120"]
    for name, actual in done:
        assert actual >= float(name[1:])  # never early


def test_stop_cuts_a_wait_short() -> None:
    stop = threading.Event()
    threading.Timer(0.05, stop.set).start()
    t0 = time.monotonic()
    wait_until(time.monotonic_ns() + 5_000_000_000, stop=stop)
    assert time.monotonic() - t0 < 2.0
