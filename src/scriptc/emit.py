"""Write a build directory: `timeline.json` plus every clip it names under `clips/`.

Clips are written first (each atomically), then the timeline replaces the old one
atomically, then clips no longer named are removed. A copy of the directory is a
complete show for one or every robot.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Mapping
from pathlib import Path

from scriptc import timeline as tl
from scriptc.cache import Entry, atomic_write
from scriptc.diagnostics import ScriptcError

TIMELINE = "timeline.json"


class OutputDir:
    """A build directory and the clips it already holds (name -> size), read once."""

    def __init__(self, path: Path) -> None:
        self.path = path
        try:
            with os.scandir(path / "clips") as it:
                self.sizes = {e.name: e.stat().st_size for e in it if e.name.endswith(".wav")}
        except OSError:
            self.sizes = {}

    def has(self, entry: Entry) -> bool:
        """True when the directory already holds this clip at the right size."""
        return self.sizes.get(tl.clip_name(entry.sha256)) == entry.size


def emit(timeline: tl.Timeline, entries: Mapping[str, Entry], out: OutputDir) -> Path:
    """Write the build directory; `entries` maps clip SHA-256 to its cache entry."""
    clips = timeline.clips()
    for clip in clips:
        entry = entries[clip.sha256]
        if out.has(entry):
            continue
        data = entry.blob.read_bytes()
        if hashlib.sha256(data).hexdigest() != clip.sha256:
            raise ScriptcError(
                f"cached clip {entry.blob} changed while building; run the build again", exit_code=2
            )
        atomic_write(out.path / clip.path, data)
    path = out.path / TIMELINE
    atomic_write(path, tl.dumps(timeline).encode("utf-8"))
    wanted = {tl.clip_name(c.sha256) for c in clips}
    present = os.listdir(out.path / "clips") if (out.path / "clips").is_dir() else []
    for name in set(present) - wanted:
        if name.endswith(".wav"):
            os.unlink(out.path / "clips" / name)
    return path
