"""A content-addressed cache of synthesised clips.

An entry is a small JSON record under `v1/meta/` named by the cache key (the
SHA-256 of everything that changes the audio) pointing at a WAV blob under
`v1/blobs/` named by the SHA-256 of its bytes. Writes go to a temporary file and
are moved into place with `os.replace`, so a reader sees a whole file or none. A
record that does not parse, or whose blob is missing, the wrong size or (when
verified) the wrong hash, is a miss: it is removed and the clip is made again.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

VERSION = 1


def cache_key(fields: dict[str, Any]) -> str:
    """SHA-256 of the canonical JSON of `fields`."""
    text = json.dumps(
        {"cache": VERSION, **fields}, sort_keys=True, ensure_ascii=False, separators=(",", ":")
    )
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def atomic_write(path: Path, data: bytes) -> None:
    """Write `data` to `path` so that readers see the old file or the new one, never a part."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


@dataclass(frozen=True, slots=True)
class Entry:
    """A cached clip: its blob, measured length and timings."""

    key: str
    sha256: str
    size: int
    sample_rate: int
    samples: int
    words: tuple[tuple[int, int, int], ...]
    marks: tuple[tuple[str, int], ...]
    blob_file: str

    @property
    def blob(self) -> Path:
        return Path(self.blob_file)

    @property
    def duration_ms(self) -> int:
        return round(self.samples * 1000 / self.sample_rate)


class AudioCache:
    def __init__(self, root: Path) -> None:
        self.root = Path(root) / f"v{VERSION}"
        # Plain strings: a warm rebuild looks up every line, and pathlib joins cost more.
        self._meta_dir = os.path.join(self.root, "meta")
        self._blob_dir = os.path.join(self.root, "blobs")

    def _meta(self, key: str) -> Path:
        return Path(os.path.join(self._meta_dir, key[:2], key + ".json"))

    def blob_path(self, sha: str) -> Path:
        return Path(self._blob_file(sha))

    def _blob_file(self, sha: str) -> str:
        return os.path.join(self._blob_dir, sha[:2], sha + ".wav")

    def get(self, key: str, *, verify: bool = False, blob: bool = True) -> Entry | None:
        """The entry for `key`, or None (and the bad record removed) if absent or damaged.

        `blob=False` reads only the record (for a clip the caller already holds); `verify`
        also checks the blob's hash.
        """
        try:
            with open(os.path.join(self._meta_dir, key[:2], key + ".json"), "rb") as f:
                raw = f.read()
        except OSError:
            return None
        try:
            d = json.loads(raw)
            entry = Entry(
                key,
                str(d["sha256"]),
                int(d["size"]),
                int(d["sample_rate"]),
                int(d["samples"]),
                tuple(map(tuple, d["words"])),
                tuple(map(tuple, d["marks"])),
                self._blob_file(str(d["sha256"])),
            )
            if d.get("key") != key or entry.sample_rate <= 0:
                raise ValueError("record does not match its key")
            if not all(len(w) == 3 for w in entry.words) or not all(
                len(m) == 2 for m in entry.marks
            ):
                raise ValueError("malformed timings")
            if blob and os.stat(entry.blob_file).st_size != entry.size:
                raise ValueError("blob has the wrong size")
            if verify and hashlib.sha256(entry.blob.read_bytes()).hexdigest() != entry.sha256:
                entry.blob.unlink()
                raise ValueError("blob has the wrong hash")
        except (OSError, ValueError, KeyError, TypeError):
            self.evict(key)
            return None
        return entry

    def evict(self, key: str) -> None:
        with contextlib.suppress(OSError):
            self._meta(key).unlink()

    def put(
        self,
        key: str,
        wav: bytes,
        *,
        sample_rate: int,
        samples: int,
        words: tuple[tuple[int, int, int], ...],
        marks: tuple[tuple[str, int], ...],
        request: dict[str, Any],
    ) -> Entry:
        """Store a clip: blob first, then the record that points at it."""
        sha = hashlib.sha256(wav).hexdigest()
        blob = self.blob_path(sha)
        try:
            intact = blob.read_bytes() == wav
        except OSError:
            intact = False
        if not intact:
            atomic_write(blob, wav)
        record = {
            "key": key,
            "sha256": sha,
            "size": len(wav),
            "sample_rate": sample_rate,
            "samples": samples,
            "words": [list(w) for w in words],
            "marks": [list(m) for m in marks],
            "request": request,
        }
        atomic_write(self._meta(key), json.dumps(record, sort_keys=True).encode("utf-8"))
        return Entry(key, sha, len(wav), sample_rate, samples, words, marks, str(blob))
