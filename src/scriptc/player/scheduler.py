"""Run events at absolute monotonic deadlines: sleep most of the way, then spin.

`wait_until` sleeps until `spin_ns` before the deadline (the sleep may overshoot by
the OS's wake-up latency) and then busy-waits the rest. With a stop event set it
returns at once, which is how Ctrl-C and faults cut a show short. Deadlines never
depend on when the previous event ran, so nothing drifts.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from scriptc.player.clock import ShowClock

DEFAULT_SPIN_NS = 1_000_000


def wait_until(
    deadline_ns: int,
    *,
    stop: threading.Event | None = None,
    spin_ns: int = DEFAULT_SPIN_NS,
    mono: Callable[[], int] = time.monotonic_ns,
) -> int:
    """Block until the monotonic clock reaches `deadline_ns`; return the time it woke."""
    while True:
        now = mono()
        remaining = deadline_ns - now
        if remaining <= 0 or (stop is not None and stop.is_set()):
            return now
        if remaining > spin_ns:
            timeout = (remaining - spin_ns) / 1e9
            if stop is not None:
                stop.wait(timeout)
            else:
                time.sleep(timeout)
        # else: spin; the loop re-reads the clock


@dataclass(order=True)
class Event:
    """Something to do at timeline time `at_ms`."""

    at_ms: float
    order: int
    kind: str = field(compare=False)
    action: Callable[[], Any] = field(compare=False, repr=False)
    info: dict[str, Any] = field(compare=False, default_factory=dict)


class Scheduler:
    """Dispatches events in time order against a `ShowClock`, logging each."""

    def __init__(
        self,
        clock: ShowClock,
        *,
        stop: threading.Event | None = None,
        spin_ns: int = DEFAULT_SPIN_NS,
        on_dispatch: Callable[[Event, float, int], None] | None = None,
    ) -> None:
        self.clock = clock
        self.stop = stop or threading.Event()
        self.spin_ns = spin_ns
        self.on_dispatch = on_dispatch
        self.follow_every_ns = 1_000_000_000

    def run(self, events: Iterable[Event]) -> None:
        last_follow = self.clock.mono()
        for ev in sorted(events):
            deadline = self.clock.deadline_ns(ev.at_ms)
            if deadline - self.clock.mono() > 2 * self.follow_every_ns:
                # A long wait: re-check the wall clock on the way so a slewed clock is followed.
                while (
                    deadline - self.clock.mono() > self.follow_every_ns and not self.stop.is_set()
                ):
                    self.stop.wait(self.follow_every_ns / 2e9)
                    self.clock.follow()
                    deadline = self.clock.deadline_ns(ev.at_ms)
            woke = wait_until(deadline, stop=self.stop, spin_ns=self.spin_ns, mono=self.clock.mono)
            if self.stop.is_set():
                return
            ev.action()
            if self.on_dispatch:
                self.on_dispatch(ev, self.clock.show_ms(woke), time.time_ns())
            if woke - last_follow > self.follow_every_ns:
                self.clock.follow()
                last_follow = woke
