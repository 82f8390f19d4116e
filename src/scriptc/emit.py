"""Write a build directory: `timeline.json` plus every clip it names under `clips/`.

Clips are written first (each atomically), then the timeline replaces the old one
atomically, then clips no longer named are removed. A copy of the directory is a
complete show for one or every robot.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping
from pathlib import Path

from scriptc import timeline as tl
from scriptc.cache import Entry, atomic_write
from scriptc.diagnostics import ScriptcError

TIMELINE = "timeline.json"


def clip_present(out_dir: Path, entry: Entry) -> bool:
    """True when the build directory already holds this clip at the right size."""
    path = out_dir / tl.Clip(entry.sha256, entry.sample_rate, entry.samples).path
    try:
        return path.stat().st_size == entry.size
    except OSError:
        return False


def emit(timeline: tl.Timeline, entries: Mapping[str, Entry], out_dir: Path) -> Path:
    """Write the build directory; `entries` maps clip SHA-256 to its cache entry."""
    for clip in timeline.clips():
        entry = entries[clip.sha256]
        if clip_present(out_dir, entry):
            continue
        data = entry.blob.read_bytes()
        if hashlib.sha256(data).hexdigest() != clip.sha256:
            raise ScriptcError(
                f"cached clip {entry.blob} changed while building; run the build again", exit_code=2
            )
        atomic_write(out_dir / clip.path, data)
    path = out_dir / TIMELINE
    atomic_write(path, tl.dumps(timeline).encode("utf-8"))
    wanted = {Path(c.path).name for c in timeline.clips()}
    for stale in (out_dir / "clips").glob("*.wav"):
        if stale.name not in wanted:
            stale.unlink()
    return path
