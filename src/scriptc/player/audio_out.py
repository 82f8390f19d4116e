"""Audio outputs: one stream for the whole show, every clip decoded before the start.

`Mixer` places each clip at the sample where its deadline falls, so audio timing is
sample-accurate, not limited by the callback period. `DeviceOutput` feeds the mixer to
a miniaudio playback device (the sound card, or miniaudio's NULL backend, which runs
in real time without one), compensating the device's buffer latency. `FileOutput`
writes exactly what was played, each clip at the offset it was actually started, to
a WAV file.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from scriptc.player import pcm as pcmlib
from scriptc.player.clock import ShowClock
from scriptc.player.eventlog import EventLog
from scriptc.player.plan import RobotPlan


class AudioError(Exception):
    """The audio output cannot be used; the message says what to do."""


@dataclass
class Voiced:
    robot: str
    cue: str
    at_ms: float
    pcm: bytes
    deadline_ns: int = 0
    pos: int = -1  # frames already played; -1 not started
    muted: bool = False


class Mixer:
    def __init__(
        self, plans: list[RobotPlan], clips: dict[str, bytes], from_ms: float, log: EventLog
    ) -> None:
        self.log = log
        decoded = {sha: pcmlib.read_wav(data) for sha, data in clips.items()}
        self.rate = max((r for _, r in decoded.values()), default=22050)
        converted = {sha: pcmlib.convert(p, r, self.rate) for sha, (p, r) in decoded.items()}
        self.items = sorted(
            (
                Voiced(plan.name, a.cue, a.start, converted[a.clip.sha256])
                for plan in plans
                for a in plan.audio
                if a.start >= from_ms
            ),
            key=lambda v: v.at_ms,
        )
        self.clock: ShowClock | None = None
        self.lock = threading.Lock()

    def arm(self, clock: ShowClock) -> None:
        self.clock = clock
        for v in self.items:
            v.deadline_ns = clock.deadline_ns(v.at_ms)

    def mute(self, robot: str) -> None:
        with self.lock:
            for v in self.items:
                if v.robot == robot:
                    v.muted = True

    def done(self) -> bool:
        return all(v.muted or v.pos >= len(v.pcm) // 2 for v in self.items)

    def render(self, frames: int, play_at_ns: int) -> bytes:
        """The next `frames` of the show, whose first frame will be heard at `play_at_ns`."""
        buf = bytearray(frames * 2)
        if self.clock is None:
            return bytes(buf)
        window_end = play_at_ns + frames * 1_000_000_000 // self.rate
        with self.lock:
            for v in self.items:
                if v.deadline_ns >= window_end:
                    break
                total = len(v.pcm) // 2
                if v.muted or v.pos >= total:
                    continue
                if v.pos < 0:
                    offset = round((v.deadline_ns - play_at_ns) * self.rate / 1e9)
                    v.pos = max(0, -offset)  # a late start skips what is already due
                    offset = max(0, offset)
                    heard = play_at_ns + offset * 1_000_000_000 // self.rate
                    self.log.write(
                        "audio",
                        robot=v.robot,
                        cue=v.cue,
                        scheduled_ms=v.at_ms,
                        actual_ms=self.clock.show_ms(heard),
                        wall_ns=time.time_ns() + (heard - time.monotonic_ns()),
                    )
                else:
                    offset = 0
                n = min(frames - offset, total - v.pos)
                pcmlib.mix_into(buf, offset, v.pcm[v.pos * 2 : (v.pos + n) * 2])
                v.pos += n
        return bytes(buf)


class DeviceOutput:
    """A miniaudio playback stream: `device` for the sound card, `null` for none in real time."""

    def __init__(
        self,
        mixer: Mixer,
        *,
        null: bool,
        buffer_ms: int = 20,
        extra_latency_ms: float = 0.0,
    ) -> None:
        self.mixer = mixer
        self.null = null
        self.buffer_ms = buffer_ms
        self.latency_ns = round((buffer_ms + extra_latency_ms) * 1e6)
        self.device: Any = None

    def start(self) -> None:
        import miniaudio

        backends = [miniaudio.Backend.NULL] if self.null else None
        try:
            self.device = miniaudio.PlaybackDevice(
                output_format=miniaudio.SampleFormat.SIGNED16,
                nchannels=1,
                sample_rate=self.mixer.rate,
                buffersize_msec=self.buffer_ms,
                backends=backends,
                app_name="scriptc",
            )
        except miniaudio.MiniaudioError as exc:
            raise AudioError(
                f"no audio output device ({exc.args[0] if exc.args else exc}); "
                "use --audio null to run without sound or --audio file:show.wav"
            ) from None
        latency = self.latency_ns
        mixer = self.mixer

        def stream() -> Any:
            frames = yield b""
            while True:
                frames = yield mixer.render(frames, time.monotonic_ns() + latency)

        gen = stream()
        next(gen)
        self.device.start(gen)

    def close(self) -> None:
        if self.device is not None:
            self.device.close()
            self.device = None


class FileOutput:
    """Records what was played, where it was played, and writes it to a WAV file."""

    def __init__(self, mixer: Mixer, path: Path, from_ms: float) -> None:
        self.mixer = mixer
        self.path = path
        self.from_ms = from_ms
        self.played: list[tuple[float, bytes]] = []
        self.lock = threading.Lock()

    def play(self, voiced: Voiced, actual_ms: float) -> None:
        with self.lock:
            if not voiced.muted:
                self.played.append((actual_ms, voiced.pcm))

    def close(self) -> None:
        rate = self.mixer.rate
        if not self.played:
            pcmlib.write_wav(str(self.path), b"", rate)
            return
        placed = [(max(0, round((t - self.from_ms) * rate / 1000)), p) for t, p in self.played]
        total = max(off + len(p) // 2 for off, p in placed)
        buf = bytearray(total * 2)
        for off, p in placed:
            pcmlib.mix_into(buf, off, p)
        pcmlib.write_wav(str(self.path), bytes(buf), rate)
