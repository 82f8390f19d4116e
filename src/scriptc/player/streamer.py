"""Stream one robot's goal positions at a fixed rate against the show clock.

One thread per robot owns its bus. Ticks fall on a fixed grid (`rate_hz`) plus the
exact start of every gesture, each at an absolute deadline. Each tick interpolates
every joint along its gesture's easing, clamps it to the joint's limits and top speed,
and sends all goals in one write. Every `check_every` ticks the servos are asked for
hardware errors. Before the show the arm glides from where it is to where the show (or
the rehearsal cue) starts. After the show, on a stop, or on a fault, it glides home.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from scriptc.easing import position_at
from scriptc.player.clock import ShowClock
from scriptc.player.eventlog import EventLog
from scriptc.player.plan import RobotPlan, glide_ms
from scriptc.player.scheduler import wait_until
from scriptc.player.servo_out import ServoFault, ServoOutput, clamp


@dataclass
class StreamStats:
    """Tick timing for benchmarks: lateness of every tick in ns."""

    late_ns: list[int] = field(default_factory=list)
    ticks: int = 0
    bus_bytes: int = 0  # over the wire during the show itself


class Streamer:
    def __init__(
        self,
        plan: RobotPlan,
        output: ServoOutput,
        log: EventLog,
        *,
        rate_hz: float = 100.0,
        check_every: int = 10,
        stop: threading.Event | None = None,
        on_fault: Callable[[str], None] | None = None,
    ) -> None:
        self.plan = plan
        self.output = output
        self.log = log
        self.period_ms = 1000.0 / rate_hz
        self.check_every = check_every
        self.stop = stop or threading.Event()
        self.on_fault = on_fault  # told the robot's name at once, e.g. to mute its audio
        self.last: dict[str, float] = {}
        self.last_t = 0.0
        self.fault: ServoFault | None = None
        self.stats = StreamStats()

    # -- before and after the show ----------------------------------------------------------

    def prepare(self, start_ms: float) -> int:
        """Connect and glide to the pose the show holds at `start_ms`; return the glide time."""
        present = self.output.open()
        self.last = dict(present)
        target = self.plan.pose_at(start_ms)
        ms = glide_ms(self.plan.joints, present, target)
        self._glide(present, target, ms, t0_ms=start_ms - ms)
        self.log.write("ready", robot=self.plan.name, glide_ms=ms)
        return ms

    def _glide(
        self,
        frm: dict[str, float],
        to: dict[str, float],
        ms: int,
        *,
        t0_ms: float,
        skip_checks: bool = False,
    ) -> None:
        """Ease from `frm` to `to` over `ms`, on the monotonic clock; `t0_ms` labels the samples
        in show time (a glide before the show ends at its start, one after it follows it)."""
        tracks = {j: ((0, frm.get(j, to[j]), "linear"), (ms, to[j], "in-out")) for j in to}
        t0 = time.monotonic_ns()
        k = 0
        while True:
            t = min(k * self.period_ms, ms)
            wait_until(t0 + round(t * 1e6))
            goals = {j: position_at(tr, t) for j, tr in tracks.items()}
            self._send(t0_ms + t, goals, check=False if skip_checks else k % self.check_every == 0)
            if t >= ms:
                return
            k += 1

    def home(self, exclude: int | None = None, *, after_ms: float = 0.0) -> None:
        """Glide every joint (but a faulted servo's) home; never raises."""
        try:
            home = {j.name: j.home for j in self.plan.joints.values() if j.id != exclude}
            if home:
                self._glide(
                    {j: self.last.get(j, home[j]) for j in home},
                    home,
                    glide_ms(self.plan.joints, self.last, home),
                    t0_ms=after_ms,
                    skip_checks=True,
                )
            self.log.write("home", robot=self.plan.name)
        except Exception as exc:
            self.log.write("home-failed", robot=self.plan.name, error=str(exc))

    # -- the show ---------------------------------------------------------------------------

    def _send(self, t_ms: float, goals: dict[str, float], *, check: bool) -> None:
        dt = self.period_ms / 1000.0
        safe = clamp(self.plan.joints, goals, self.last, dt * 1.05)
        self.output.write(t_ms, safe)
        self.last.update(safe)
        self.last_t = t_ms
        if check:
            self.output.check()

    def ticks(self, start_ms: float, end_ms: float) -> list[float]:
        grid = [
            start_ms + k * self.period_ms
            for k in range(int((end_ms - start_ms) / self.period_ms) + 1)
        ]
        starts = [m.start for m in self.plan.motion if start_ms <= m.start <= end_ms]
        return sorted({*grid, *starts, end_ms})

    def run(self, clock: ShowClock, start_ms: float, end_ms: float) -> None:
        """Stream from `start_ms` to `end_ms` (timeline times), then glide home."""
        pending = [m for m in self.plan.motion if m.start >= start_ms]
        bytes_before = self.output.bus_bytes()
        try:
            for k, t in enumerate(self.ticks(start_ms, end_ms)):
                deadline = clock.deadline_ns(t)
                woke = wait_until(deadline, stop=self.stop, mono=clock.mono)
                if self.stop.is_set():
                    break
                self.stats.late_ns.append(woke - deadline)
                self._send(
                    t, self.plan.pose_at(t), check=k % self.check_every == self.check_every - 1
                )
                self.stats.ticks += 1
                while pending and pending[0].start <= t:
                    m = pending.pop(0)
                    self.log.write(
                        "motion",
                        robot=self.plan.name,
                        cue=m.cue,
                        gesture=m.gesture,
                        scheduled_ms=m.start,
                        actual_ms=clock.show_ms(woke),
                        wall_ns=time.time_ns(),
                    )
        except ServoFault as exc:
            self.fault = exc
            if self.on_fault:
                self.on_fault(self.plan.name)
            self.log.write(
                "fault",
                robot=self.plan.name,
                error=str(exc),
                servo=exc.servo,
                actual_ms=clock.show_ms(),
            )
            self.home(exclude=exc.servo, after_ms=self.last_t)
            return
        except Exception as exc:  # the bus must still be left safe
            self.fault = ServoFault(f"{self.plan.name}: {exc!r}")
            if self.on_fault:
                self.on_fault(self.plan.name)
            self.log.write("fault", robot=self.plan.name, error=repr(exc))
            self.home(after_ms=self.last_t)
            return
        self.stats.bus_bytes = self.output.bus_bytes() - bytes_before
        self.home(after_ms=self.last_t)
