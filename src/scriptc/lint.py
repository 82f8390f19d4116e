"""The lint stage: load, parse, lay out with the best durations known, run every check.

Lint never synthesises. It uses clips already in the cache for exact timing and
estimates the rest, and it imports neither boto3 nor the audio stack.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from scriptc import checks, parse, source
from scriptc.diagnostics import Report
from scriptc.layout import ClipInfo, Layout, layout
from scriptc.model import Play


@dataclass(slots=True)
class LintResult:
    source: source.Source | None
    play: Play | None
    layout: Layout | None
    report: Report
    engine: str


def cached_clips(play: Play, engine: str, cache_dir: Path) -> dict[str, ClipInfo]:
    """Exact clip facts for lines whose audio is already cached."""
    from scriptc.cache import AudioCache
    from scriptc.synth import cached_only
    from scriptc.voices import registry
    from scriptc.voices.base import VoiceError

    try:
        backend = registry.get(engine)
    except VoiceError:
        return {}
    entries = cached_only(play, backend, AudioCache(cache_dir))
    return {
        cue: ClipInfo(e.duration_ms, e.words, e.marks, exact=True) for cue, e in entries.items()
    }


def lint(
    path: Path,
    *,
    engine: str | None = None,
    cache_dir: Path | None = None,
    clips: Mapping[str, ClipInfo] | None = None,
    timing: bool = True,
) -> LintResult:
    """Check the screenplay at `path` and everything it includes.

    With `timing=False` nothing is laid out and the timing checks are skipped: the
    build does that once, with measured clips.
    """
    report = Report()
    src = source.load(path, report)
    play = parse.parse(src, report) if src is not None else None
    if play is None:
        return LintResult(src, None, None, report, engine or "espeak")
    engine = engine or play.defaults.engine
    placed = None
    if timing:
        if clips is None:
            clips = cached_clips(play, engine, cache_dir) if cache_dir is not None else {}
        placed = layout(play, clips, report)
    # Without a layout only the checks that read the play alone can run; the build runs
    # the timing checks once it has measured every clip.
    report.extend(
        checks.run_all(checks.Context(play, placed, engine), timing=None if timing else False)
    )
    return LintResult(src, play, placed, report, engine)
