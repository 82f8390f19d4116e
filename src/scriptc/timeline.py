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
        return "clips/" + clip_name(self.sha256)


def clip_name(sha256: str) -> str:
    """A clip's file name in a build directory: the start of its SHA-256."""
    return sha256[:24] + ".wav"


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


def _one_line(value: Any) -> str:
    return json.dumps(
        value, sort_keys=True, ensure_ascii=False, allow_nan=False, separators=(", ", ": ")
    )


def _write(value: Any, indent: int, depth: int, out: list[str]) -> None:
    """Indent mappings and lists down to `depth` levels; below that, one value per line."""
    pad = "  " * indent
    if depth == 0 or not isinstance(value, (dict, list)) or not value:
        out.append(_one_line(value))
        return
    if isinstance(value, dict):
        out.append("{\n")
        for i, key in enumerate(sorted(value)):
            out.append(f"{pad}  {_one_line(key)}: ")
            _write(value[key], indent + 1, depth - 1, out)
            out.append(",\n" if i < len(value) - 1 else "\n")
        out.append(pad + "}")
    else:
        out.append("[\n")
        for i, item in enumerate(value):
            out.append(pad + "  ")
            _write(item, indent + 1, depth - 1, out)
            out.append(",\n" if i < len(value) - 1 else "\n")
        out.append(pad + "]")


def dumps(tl: Timeline) -> str:
    """Canonical JSON text of the timeline: sorted keys, one event per line.

    The structure down to each robot's event lists is indented; every event, cue and
    scene is one line of compact JSON, so goldens diff an event at a time and the
    whole file is written by the C encoder in a few calls.
    """
    data = to_data(tl)
    out: list[str] = ["{\n"]
    keys = sorted(data)
    for i, key in enumerate(keys):
        out.append(f"  {_one_line(key)}: ")
        depth = {"robots": 3, "scenes": 1, "cues": 1}.get(key, 0)
        _write(data[key], 1, depth, out)
        out.append(",\n" if i < len(keys) - 1 else "\n")
    out.append("}\n")
    return "".join(out)


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
