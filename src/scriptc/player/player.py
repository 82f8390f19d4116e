"""Perform a built timeline: one robot's part, or every robot's, against one shared clock.

Order of a run: read and verify the timeline and clips, check the host clock against a
time server if asked, connect the servos and glide them to the starting pose, open
the audio stream, wait for the start instant (given, or from an OSC go), then stream
servos and audio against absolute deadlines until the end, a stop or a fault, and
send every servo home. Everything that happens goes to the event log.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from scriptc.player import plan as planlib
from scriptc.player import timesync
from scriptc.player.audio_out import AudioError, DeviceOutput, FileOutput, Mixer
from scriptc.player.clock import ShowClock, format_instant
from scriptc.player.eventlog import EventLog
from scriptc.player.scheduler import Event, Scheduler
from scriptc.player.servo_out import ServoFault, ServoOutput, SimOutput
from scriptc.player.streamer import Streamer

EXIT_OK, EXIT_REFUSED, EXIT_FAULT, EXIT_STOPPED = 0, 1, 3, 130


class PlayerError(Exception):
    """The show cannot start; nothing has moved. `exit_code` says how the CLI exits."""

    def __init__(self, message: str, exit_code: int = EXIT_REFUSED) -> None:
        super().__init__(message)
        self.exit_code = exit_code


@dataclass
class Start:
    """When the show starts: an absolute wall-clock instant, a delay, or an OSC go."""

    at_wall_ns: int | None = None
    in_ms: int | None = None
    osc: tuple[str, int] | None = None


@dataclass
class PlayOptions:
    build_dir: Path
    robots: list[str]
    start: Start
    audio: str = "null"  # device | null | file:PATH | none
    servos: str = "sim"  # dynamixel | sim | none
    port: str | None = None
    from_cue: str | None = None
    log_path: Path | None = None
    rate_hz: float = 100.0
    ntp: str | None = None
    max_offset_ms: float = 5.0
    out_dir: Path | None = None
    audio_latency_ms: float = 0.0
    buffer_ms: int = 20


@dataclass
class PlayResult:
    exit_code: int
    log: EventLog
    streamers: list[Streamer] = field(default_factory=list)
    faults: list[str] = field(default_factory=list)


def _servo_output(opts: PlayOptions, plan: planlib.RobotPlan, single: bool) -> ServoOutput | None:
    if opts.servos == "none" or not plan.joints:
        return None
    if opts.servos == "sim":
        lines = [(a.start, a.duration, a.text) for a in plan.audio]
        return SimOutput(plan.name, plan.joints, opts.out_dir, lines)
    if opts.servos != "dynamixel":
        raise PlayerError(f"unknown servo output {opts.servos!r}: use dynamixel, sim or none", 2)
    if plan.bus is None and opts.port is None:
        raise PlayerError(
            f"{plan.name} has no `bus:` in the screenplay; give --port or use --servos sim", 2
        )
    from scriptc.player.dynamixel_out import DynamixelOutput

    return DynamixelOutput(
        plan.name, plan.joints, plan.bus or {}, port=opts.port if single else None
    )


def _prepare_all(streamers: list[Streamer], from_ms: int) -> None:
    """Connect every robot's servos and glide them to the starting pose, all at once."""
    errors: list[ServoFault] = []

    def prepare(s: Streamer) -> None:
        try:
            s.prepare(from_ms)
        except ServoFault as exc:
            errors.append(exc)

    threads = [threading.Thread(target=prepare, args=(s,)) for s in streamers]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:  # nothing has started: refuse, as for any other reason not to start
        raise PlayerError("; ".join(str(e) for e in errors), EXIT_REFUSED)


def check_clock(ntp: str, bound_ms: float, log: EventLog) -> timesync.Measurement:
    try:
        m = timesync.offset(ntp)
    except timesync.TimeSyncError as exc:
        raise PlayerError(f"cannot check the clock: {exc}") from None
    log.write("clock", server=ntp, offset_ms=round(m.offset_ms, 3), delay_ms=round(m.delay_ms, 3))
    if abs(m.offset_ms) > bound_ms:
        raise PlayerError(
            f"this host's clock is {m.offset_ms:+.1f} ms off {ntp} (bound {bound_ms} ms); "
            "fix time sync (chronyc tracking) before the show"
        )
    return m


def _wait_for_go(listener: Any, stop: threading.Event, log: EventLog) -> tuple[int, str | None]:
    """Block until an OSC go (its start instant and cue) or a stop arrives."""
    log.write("waiting", osc_port=listener.port)
    while not stop.is_set():
        go = listener.wait(0.2)
        if listener.stopped.is_set():
            stop.set()
            break
        if go is not None:
            log.write("go", start=format_instant(go.start_wall_ns), cue=go.cue)
            return go.start_wall_ns, go.cue
    raise PlayerError("stopped before the show started", EXIT_STOPPED)


def perform(opts: PlayOptions, *, stop: threading.Event | None = None) -> PlayResult:
    """Run the show; return its exit code and log. Raises `PlayerError` if it cannot start."""
    stop = stop or threading.Event()
    requested = time.time_ns()
    start_at = opts.start.at_wall_ns
    if opts.start.in_ms is not None:
        start_at = requested + opts.start.in_ms * 1_000_000
    timeline = planlib.load(opts.build_dir)
    plans = planlib.robots(timeline, opts.robots)
    log = EventLog(opts.log_path)
    if opts.ntp:
        check_clock(opts.ntp, opts.max_offset_ms, log)

    listener = None
    if opts.start.osc is not None and start_at is None:
        from scriptc.player.osc import GoListener

        try:
            listener = GoListener(*opts.start.osc)
        except OSError as exc:
            raise PlayerError(
                f"cannot listen for OSC on {opts.start.osc[0]}:{opts.start.osc[1]}: {exc}"
            ) from None

    from_ms = planlib.start_of(timeline, opts.from_cue)
    clips = planlib.read_clips(opts.build_dir, plans, from_ms)
    mixer = Mixer(plans, clips, from_ms, log)
    streamers: list[Streamer] = []
    device: DeviceOutput | None = None
    file_out: FileOutput | None = None
    try:
        for plan in plans:
            output = _servo_output(opts, plan, single=len(plans) == 1)
            if output is not None:
                streamers.append(
                    Streamer(
                        plan, output, log, rate_hz=opts.rate_hz, stop=stop, on_fault=mixer.mute
                    )
                )
        _prepare_all(streamers, from_ms)
        if opts.audio in ("device", "null"):
            device = DeviceOutput(
                mixer,
                null=opts.audio == "null",
                buffer_ms=opts.buffer_ms,
                extra_latency_ms=opts.audio_latency_ms,
            )
            try:
                device.start()
            except AudioError as exc:
                raise PlayerError(str(exc)) from None
        elif opts.audio.startswith("file:"):
            file_out = FileOutput(mixer, Path(opts.audio[5:]), from_ms)
        elif opts.audio != "none":
            raise PlayerError(
                f"unknown audio output {opts.audio!r}: use device, null, file:PATH or none", 2
            )

        if start_at is None:
            start_at, cue = _wait_for_go(listener, stop, log)
            if cue and cue != opts.from_cue:
                raise PlayerError(f"the go message asks for cue {cue!r}; restart with --from {cue}")
        if start_at < time.time_ns() - 20_000_000:
            raise PlayerError(
                f"the start instant {format_instant(start_at)} has already passed "
                "(the servos took too long to get ready?); allow more time"
            )
        return _run(opts, plans, streamers, mixer, file_out, log, start_at, from_ms, stop)
    finally:
        if device is not None:
            device.close()
        if listener is not None:
            listener.close()
        for s in streamers:
            s.output.close()
        if file_out is not None:
            file_out.close()
        log.close()


def _nothing() -> None:
    """Events whose work happens in the dispatch callback."""


def _run(
    opts: PlayOptions,
    plans: list[planlib.RobotPlan],
    streamers: list[Streamer],
    mixer: Mixer,
    file_out: FileOutput | None,
    log: EventLog,
    start_at: int,
    from_ms: int,
    stop: threading.Event,
) -> PlayResult:
    clock = ShowClock(start_at, origin_ms=from_ms)
    end_ms = max((p.end_ms() for p in plans), default=from_ms)
    mixer.arm(clock)
    log.write(
        "start",
        start=format_instant(start_at),
        from_ms=from_ms,
        end_ms=end_ms,
        robots=[p.name for p in plans],
    )
    threads = [
        threading.Thread(target=s.run, args=(clock, from_ms, end_ms), name=f"servo-{s.plan.name}")
        for s in streamers
    ]
    events: list[Event] = []
    if file_out is not None:
        for i, v in enumerate(mixer.items):
            events.append(Event(v.at_ms, i, "audio", _nothing, {"voiced": v}))

    def dispatched(ev: Event, actual_ms: float, wall_ns: int) -> None:
        v = ev.info["voiced"]
        assert file_out is not None
        file_out.play(v, actual_ms)
        log.write(
            "audio",
            robot=v.robot,
            cue=v.cue,
            scheduled_ms=v.at_ms,
            actual_ms=actual_ms,
            wall_ns=wall_ns,
        )

    events.append(Event(end_ms, len(events), "end", _nothing))

    def on_dispatch(ev: Event, actual_ms: float, wall_ns: int) -> None:
        if ev.kind == "audio":
            dispatched(ev, actual_ms, wall_ns)

    scheduler = Scheduler(clock, stop=stop, on_dispatch=on_dispatch)
    for t in threads:
        t.start()
    sched = threading.Thread(target=scheduler.run, args=(events,), name="scheduler")
    sched.start()
    for t in [*threads, sched]:
        while t.is_alive():  # joined in steps so signal handlers run in this thread
            t.join(0.1)
    # Let the last clip ring out on a live stream.
    tail_end = time.monotonic() + 2.0
    while (
        not stop.is_set() and not mixer.done() and file_out is None and time.monotonic() < tail_end
    ):
        time.sleep(0.02)
    faults = [str(s.fault) for s in streamers if s.fault is not None]
    code = EXIT_FAULT if faults else EXIT_STOPPED if stop.is_set() else EXIT_OK
    log.write(
        "end",
        status={EXIT_OK: "ok", EXIT_FAULT: "fault", EXIT_STOPPED: "stopped"}[code],
        actual_ms=clock.show_ms(),
        faults=faults,
    )
    return PlayResult(code, log, streamers, faults)


def schedule_rows(
    build_dir: Path, robots: list[str], from_cue: str | None
) -> list[tuple[int, str, str, str, str]]:
    """The dry-run table: every event these robots would perform from the start cue."""
    timeline = planlib.load(build_dir)
    plans = planlib.robots(timeline, robots)
    from_ms = planlib.start_of(timeline, from_cue)
    rows = []
    for p in plans:
        rows += [(a.start, p.name, "audio", a.cue, a.text) for a in p.audio if a.start >= from_ms]
        rows += [
            (m.start, p.name, "motion", m.cue, f"{m.gesture} ({', '.join(m.tracks)})")
            for m in p.motion
            if m.start >= from_ms
        ]
    return sorted(rows)
