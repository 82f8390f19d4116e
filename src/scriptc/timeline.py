"""The compiled timeline: what every robot says and does, when, in integer milliseconds.

`dumps` writes canonical JSON (sorted keys, two-space indent, trailing newline,
floats rounded to micro-radians, no dates or absolute paths) so the same inputs
give the same bytes. `loads` reads it back and checks the format version.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

FORMAT = "scriptc.timeline/1"


@dataclass(frozen=True, slots=True)
class Clip:
    """A clip file in the build directory, named by the SHA-256 of its bytes."""

    sha256: str
    sample_rate: int
    samples: int

    @property
    def path(self) -> str:
        return f"clips/{self.sha256[:24]}.wav"


@dataclass(frozen=True, slots=True)
class AudioEvent:
    start: int
    duration: int
    cue: str
    scene: str
    text: str
    clip: Clip
    words: tuple[tuple[int, str], ...] = ()


@dataclass(frozen=True, slots=True)
class MotionEvent:
    start: int
    duration: int
    cue: str
    scene: str
    gesture: str
    tracks: dict[str, tuple[tuple[int, float, str], ...]]


@dataclass(frozen=True, slots=True)
class RobotPart:
    name: str
    hardware: dict[str, Any]
    audio: tuple[AudioEvent, ...] = ()
    motion: tuple[MotionEvent, ...] = ()


@dataclass(frozen=True, slots=True)
class CueMark:
    id: str
    scene: str
    start: int
    robot: str


@dataclass(frozen=True, slots=True)
class SceneMark:
    id: str
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Timeline:
    title: str
    duration: int
    engine: str
    scenes: tuple[SceneMark, ...]
    cues: tuple[CueMark, ...]
    robots: dict[str, RobotPart] = field(default_factory=dict)

    def clips(self) -> list[Clip]:
        seen: dict[str, Clip] = {}
        for part in self.robots.values():
            for a in part.audio:
                seen.setdefault(a.clip.sha256, a.clip)
        return [seen[k] for k in sorted(seen)]


def _rad(x: float) -> float:
    r = round(x, 6)
    return 0.0 if r == 0 else r


def to_data(tl: Timeline) -> dict[str, Any]:
    """The timeline as plain JSON data."""
    robots: dict[str, Any] = {}
    for name, part in tl.robots.items():
        robots[name] = {
            "hardware": part.hardware,
            "audio": [
                {
                    "start": a.start,
                    "duration": a.duration,
                    "cue": a.cue,
                    "scene": a.scene,
                    "text": a.text,
                    "clip": {
                        "path": a.clip.path,
                        "sha256": a.clip.sha256,
                        "sample_rate": a.clip.sample_rate,
                        "samples": a.clip.samples,
                    },
                    "words": [[t, w] for t, w in a.words],
                }
                for a in part.audio
            ],
            "motion": [
                {
                    "start": m.start,
                    "duration": m.duration,
                    "cue": m.cue,
                    "scene": m.scene,
                    "gesture": m.gesture,
                    "tracks": {
                        j: [[t, _rad(p), e] for t, p, e in tr] for j, tr in m.tracks.items()
                    },
                }
                for m in part.motion
            ],
        }
    return {
        "format": FORMAT,
        "title": tl.title,
        "duration": tl.duration,
        "engine": tl.engine,
        "scenes": [{"id": s.id, "start": s.start, "end": s.end} for s in tl.scenes],
        "cues": [
            {"id": c.id, "scene": c.scene, "start": c.start, "robot": c.robot} for c in tl.cues
        ],
        "robots": robots,
    }


def dumps(tl: Timeline) -> str:
    """Canonical JSON text of the timeline."""
    return (
        json.dumps(to_data(tl), sort_keys=True, indent=2, ensure_ascii=False, allow_nan=False)
        + "\n"
    )


class TimelineError(ValueError):
    """A timeline file is not one this version of scriptc can read."""


def from_data(data: Any) -> Timeline:
    """Rebuild a `Timeline` from JSON data, checking the format version."""
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        found = data.get("format") if isinstance(data, dict) else type(data).__name__
        raise TimelineError(
            f"not a {FORMAT} timeline (format: {found!r}); rebuild it with scriptc build"
        )
    try:
        robots = {}
        for name, r in data["robots"].items():
            audio = tuple(
                AudioEvent(
                    a["start"],
                    a["duration"],
                    a["cue"],
                    a["scene"],
                    a["text"],
                    Clip(a["clip"]["sha256"], a["clip"]["sample_rate"], a["clip"]["samples"]),
                    tuple((int(t), str(w)) for t, w in a["words"]),
                )
                for a in r["audio"]
            )
            motion = tuple(
                MotionEvent(
                    m["start"],
                    m["duration"],
                    m["cue"],
                    m["scene"],
                    m["gesture"],
                    {
                        j: tuple((int(t), float(p), str(e)) for t, p, e in tr)
                        for j, tr in m["tracks"].items()
                    },
                )
                for m in r["motion"]
            )
            robots[name] = RobotPart(name, r["hardware"], audio, motion)
        return Timeline(
            data["title"],
            data["duration"],
            data["engine"],
            tuple(SceneMark(s["id"], s["start"], s["end"]) for s in data["scenes"]),
            tuple(CueMark(c["id"], c["scene"], c["start"], c["robot"]) for c in data["cues"]),
            robots,
        )
    except (KeyError, TypeError, ValueError, AttributeError) as exc:
        raise TimelineError(f"timeline is damaged: {exc!r}") from None


def loads(text: str) -> Timeline:
    try:
        return from_data(json.loads(text))
    except json.JSONDecodeError as exc:
        raise TimelineError(f"timeline is not JSON: {exc}") from None
