"""The screenplay as frozen values: cast, hardware, gestures, scenes and cues.

Every value keeps the `Span` it came from so later stages can point at the source.
Times are integer milliseconds, angles radians, speeds radians per second.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from scriptc.diagnostics import Span

Ease = Literal["linear", "in", "out", "in-out", "step"]
EASES: tuple[str, ...] = ("linear", "in", "out", "in-out", "step")


@dataclass(frozen=True, slots=True)
class Voice:
    """How one robot sounds on one engine."""

    engine: str
    id: str
    span: Span
    lang: str | None = None
    options: tuple[tuple[str, str | int | float], ...] = ()


@dataclass(frozen=True, slots=True)
class Bus:
    """The serial bus of a robot's servos."""

    port: str
    baud: int
    protocol: int
    model: str
    span: Span


@dataclass(frozen=True, slots=True)
class Joint:
    """One servo: its Dynamixel id, limits, home and top speed."""

    name: str
    id: int
    min: float
    max: float
    home: float
    max_speed: float | None
    span: Span


@dataclass(frozen=True, slots=True)
class Robot:
    name: str
    span: Span
    voices: dict[str, Voice] = field(default_factory=dict)
    bus: Bus | None = None
    joints: dict[str, Joint] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class Target:
    joint: str
    rad: float
    span: Span


@dataclass(frozen=True, slots=True)
class Keyframe:
    """Joint targets to reach `at_ms` after the gesture (or loop) starts."""

    at_ms: int
    targets: tuple[Target, ...]
    ease: str
    span: Span


@dataclass(frozen=True, slots=True)
class Gesture:
    """Keyframes played once, then `loop` keyframes `repeat` times, then home or hold."""

    name: str
    keyframes: tuple[Keyframe, ...]
    loop: tuple[Keyframe, ...]
    repeat: int
    then: str
    return_ms: int | None
    span: Span

    def joints(self) -> list[str]:
        seen: dict[str, None] = {}
        for kf in (*self.keyframes, *self.loop):
            for t in kf.targets:
                seen.setdefault(t.joint)
        return list(seen)


@dataclass(frozen=True, slots=True)
class Ref:
    """A reference to an earlier cue (`previous` or a cue id) plus an offset."""

    cue: str
    offset_ms: int
    span: Span


@dataclass(frozen=True, slots=True)
class Placement:
    """Where an item starts: after the cursor with a gap, `with`/`after` a cue,
    overlapping the previous line, or `at` an offset from the scene start."""

    kind: Literal["gap", "with", "after", "overlap", "at"]
    ms: int
    span: Span
    ref: Ref | None = None


@dataclass(frozen=True, slots=True)
class Anchor:
    """Where in a line a gesture starts: start, end, a word, an SSML mark or a time."""

    kind: Literal["start", "end", "word", "mark", "time"]
    offset_ms: int
    span: Span
    index: int | None = None
    text: str | None = None


@dataclass(frozen=True, slots=True)
class GestureCue:
    gesture: str
    robot: str
    anchor: Anchor
    span: Span
    cue: str | None = None


@dataclass(frozen=True, slots=True)
class Line:
    robot: str
    text: str
    ssml: bool
    cue: str
    placement: Placement
    gestures: tuple[GestureCue, ...]
    span: Span
    text_span: Span


@dataclass(frozen=True, slots=True)
class Pause:
    ms: int
    span: Span


@dataclass(frozen=True, slots=True)
class Motion:
    """A gesture-only cue: a robot moves without speaking."""

    robot: str
    gesture: str
    cue: str
    placement: Placement
    wait: bool
    span: Span


Item = Line | Pause | Motion


@dataclass(frozen=True, slots=True)
class Scene:
    id: str
    items: tuple[Item, ...]
    gap_ms: int
    span: Span


@dataclass(frozen=True, slots=True)
class PollySettings:
    engine: str = "standard"
    format: str = "pcm"
    sample_rate: int = 16000
    lexicons: tuple[str, ...] = ()
    region: str | None = None


@dataclass(frozen=True, slots=True)
class Defaults:
    gap_ms: int = 250
    scene_gap_ms: int = 1000
    engine: str = "espeak"
    polly: PollySettings = PollySettings()


@dataclass(frozen=True, slots=True)
class Play:
    title: str
    robots: dict[str, Robot]
    gestures: dict[str, Gesture]
    scenes: tuple[Scene, ...]
    defaults: Defaults
    span: Span

    def lines(self) -> list[Line]:
        return [i for s in self.scenes for i in s.items if isinstance(i, Line)]
