"""The build stage: lint, synthesise (or reuse) every clip, lay out exactly, emit.

Nothing is written to the output directory unless every step succeeds.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from scriptc import checks, emit
from scriptc import timeline as tl
from scriptc.cache import AudioCache, Entry
from scriptc.diagnostics import Report, ScriptcError, Severity
from scriptc.layout import ClipInfo, Layout, layout
from scriptc.lint import lint
from scriptc.model import Play
from scriptc.synth import Progress, clips_for
from scriptc.voices import registry
from scriptc.voices.base import VoiceError


@dataclass(slots=True)
class BuildResult:
    timeline: tl.Timeline
    path: Path
    synthesized: int
    report: Report


def hardware(play: Play, robot: str) -> dict[str, object]:
    r = play.robots[robot]
    bus = None
    if r.bus is not None:
        bus = {
            "port": r.bus.port,
            "baud": r.bus.baud,
            "protocol": r.bus.protocol,
            "model": r.bus.model,
        }
    joints = {
        j.name: {
            "id": j.id,
            "min": round(j.min, 6),
            "max": round(j.max, 6),
            "home": round(j.home, 6),
            "max_speed": None if j.max_speed is None else round(j.max_speed, 6),
        }
        for j in r.joints.values()
    }
    return {"bus": bus, "joints": joints}


def to_timeline(play: Play, placed: Layout, entries: dict[str, Entry], engine: str) -> tl.Timeline:
    audio: dict[str, list[tl.AudioEvent]] = {name: [] for name in play.robots}
    motion: dict[str, list[tl.MotionEvent]] = {name: [] for name in play.robots}
    cues: list[tl.CueMark] = []
    for pl in placed.lines:
        e = entries[pl.line.cue]
        clip = tl.Clip(e.sha256, e.sample_rate, e.samples)
        text = pl.line.text
        words = tuple((ms, text[a:b]) for a, b, ms in e.words)
        audio[pl.line.robot].append(
            tl.AudioEvent(pl.start, pl.end - pl.start, pl.line.cue, pl.scene, text, clip, words)
        )
        cues.append(tl.CueMark(pl.line.cue, pl.scene, pl.start, pl.line.robot))
    for pm in placed.motions:
        if pm.expanded is None:
            continue
        tracks = {
            j: tuple((pm.start + t, p, ease) for t, p, ease in tr)
            for j, tr in sorted(pm.expanded.tracks.items())
        }
        motion[pm.robot].append(
            tl.MotionEvent(pm.start, pm.expanded.duration_ms, pm.cue, pm.scene, pm.gesture, tracks)
        )
        if not any(c.id == pm.cue for c in cues):
            cues.append(tl.CueMark(pm.cue, pm.scene, pm.start, pm.robot))
    robots = {
        name: tl.RobotPart(
            name,
            hardware(play, name),
            tuple(sorted(audio[name], key=lambda a: (a.start, a.cue))),
            tuple(sorted(motion[name], key=lambda m: (m.start, m.cue, m.gesture))),
        )
        for name in sorted(play.robots)
    }
    end = max([placed.duration, *(m.start + m.duration for r in robots.values() for m in r.motion)])
    return tl.Timeline(
        play.title,
        end,
        engine,
        tuple(tl.SceneMark(s, a, b) for s, a, b in placed.scenes),
        tuple(sorted(cues, key=lambda c: (c.start, c.id))),
        robots,
    )


def build(
    path: Path,
    out_dir: Path | None = None,
    *,
    engine: str | None = None,
    cache_dir: Path = Path("audio_cache"),
    jobs: int = 2,
    progress: Progress | None = None,
) -> BuildResult:
    """Compile the screenplay at `path` into `out_dir` (default `build/<play name>`)."""
    checked = lint(path, engine=engine, timing=False)
    play = checked.play
    if checked.report.has_errors or play is None:
        raise ScriptcError(list(checked.report))
    engine = checked.engine
    out_dir = out_dir or Path("build") / path.stem
    out = emit.OutputDir(out_dir)
    try:
        backend = registry.get(engine)
        entries, synthesized = clips_for(
            play,
            backend,
            AudioCache(cache_dir),
            workers=jobs,
            present=out.has,
            progress=progress,
        )
    except VoiceError as exc:
        span = next((ln.span for ln in play.lines() if ln.cue == exc.cue), play.span)
        report = Report()
        report.error(span, "E080", str(exc), exc.hint)
        raise ScriptcError(list(report)) from None
    clips = {
        cue: ClipInfo(e.duration_ms, e.words, e.marks, exact=True) for cue, e in entries.items()
    }
    report = Report()
    report.extend(d for d in checked.report if d.severity < Severity.ERROR)
    placed = layout(play, clips, report)
    report.extend(checks.run_all(checks.Context(play, placed, engine), timing=True))
    if report.has_errors:
        raise ScriptcError(list(report))
    timeline = to_timeline(play, placed, entries, engine)
    by_sha = {e.sha256: e for e in entries.values()}
    written = emit.emit(timeline, by_sha, out)
    return BuildResult(timeline, written, synthesized, report)
