"""Get a measured clip for every line: from the cache, or from the voice backend.

A rebuild with nothing changed is all cache hits and makes no synthesis call.
Clips already present (same size) in the output directory skip hash verification;
any other hit is verified before it is trusted.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from scriptc.audio import measure
from scriptc.cache import AudioCache, Entry, cache_key
from scriptc.model import Line, Play
from scriptc.voices.base import Backend, Synthesized, SynthJob, VoiceError

Progress = Callable[[int, int], None]


def job_for(backend: Backend, play: Play, line: Line) -> SynthJob:
    robot = play.robots.get(line.robot)
    voice = robot.voices.get(backend.name) if robot else None
    return backend.job(line.cue, line.text, line.ssml, voice, play.defaults.polly)


def key_for(backend: Backend, job: SynthJob) -> str:
    """The cache key: everything about the job that changes the audio (not its cue)."""
    fields = {
        "text": job.text,
        "ssml": job.ssml,
        "voice": job.voice,
        "lang": job.lang,
        "settings": [list(kv) for kv in job.settings],
    }
    return cache_key({**backend.identity(), **fields})


def clips_for(
    play: Play,
    backend: Backend,
    cache: AudioCache,
    *,
    workers: int = 2,
    present: Callable[[Entry], bool] = lambda e: False,
    progress: Progress | None = None,
) -> tuple[dict[str, Entry], int]:
    """Return a cache entry per line cue, and how many lines were synthesised."""
    entries: dict[str, Entry] = {}
    missing: dict[str, tuple[SynthJob, list[str]]] = {}
    for line in play.lines():
        job = job_for(backend, play, line)
        key = key_for(backend, job)
        if key in missing:
            missing[key][1].append(line.cue)
            continue
        # A clip already in the output directory needs only its record; any other hit
        # is hash-verified before it is trusted.
        entry = cache.get(key, blob=False)
        if entry is not None and not present(entry):
            entry = cache.get(key, verify=True)
        if entry is None:
            missing[key] = (job, [line.cue])
        else:
            entries[line.cue] = entry
    total = len(missing)
    if progress:
        progress(0, total)
    by_job = {job: (key, cues) for key, (job, cues) in missing.items()}
    done = 0

    def on_done(job: SynthJob, result: Synthesized) -> None:
        nonlocal done
        key, cues = by_job[job]
        try:
            measured = measure(result.wav)
        except Exception as exc:
            raise VoiceError(
                f"{backend.name} returned audio that cannot be read: {exc}", cue=job.cue
            ) from None
        entry = cache.put(
            key,
            result.wav,
            sample_rate=measured.sample_rate,
            samples=measured.samples,
            words=result.words,
            marks=result.marks,
            request={**backend.identity(), "voice": job.voice, "text": job.text},
        )
        for cue in cues:
            entries[cue] = entry
        done += 1
        if progress:
            progress(done, total)

    if missing:
        backend.synthesize([job for job, _ in missing.values()], workers=workers, on_done=on_done)
    return entries, total


def cached_only(play: Play, backend: Backend, cache: AudioCache) -> dict[str, Entry]:
    """Entries already in the cache (no synthesis): lint uses them for exact timing."""
    out: dict[str, Entry] = {}
    for line in play.lines():
        try:
            job = job_for(backend, play, line)
        except VoiceError:
            continue
        entry = cache.get(key_for(backend, job))
        if entry is not None:
            out[line.cue] = entry
    return out


def default_cache_dir() -> Path:
    import os

    return Path(os.environ.get("SCRIPTC_CACHE", "audio_cache"))
