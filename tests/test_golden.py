"""Golden timelines: each folder under tests/golden is a play and its expected timeline.

A case is `play.yaml` (its first line may be `# flags: ...`) or a `case.txt` naming
the play, flags and the package versions it needs. `pytest --update-goldens`
rewrites every `expected.json` from the current compiler.
"""

from __future__ import annotations

import hashlib
import shlex
from importlib.metadata import version
from pathlib import Path

import pytest

from scriptc.build import build
from scriptc.timeline import dumps, loads

GOLDEN = Path(__file__).parent / "golden"
CASES = sorted(p for p in GOLDEN.iterdir() if p.is_dir())


def _case(folder: Path) -> tuple[Path, list[str], list[str]]:
    spec: dict[str, str] = {}
    meta = folder / "case.txt"
    if meta.exists():
        for line in meta.read_text(encoding="utf-8").splitlines():
            if line.strip() and not line.startswith("#"):
                key, _, value = line.partition(":")
                spec[key.strip()] = value.strip()
    play = (folder / spec.get("play", "play.yaml")).resolve()
    flags = spec.get("flags", "")
    first = play.read_text(encoding="utf-8").splitlines()[0]
    if not flags and first.startswith("# flags:"):
        flags = first.partition(":")[2]
    return play, shlex.split(flags), spec.get("requires", "").split()


def _engine(flags: list[str]) -> str | None:
    return flags[flags.index("--engine") + 1] if "--engine" in flags else None


@pytest.mark.parametrize("folder", CASES, ids=lambda p: p.name)
def test_golden_timeline(folder: Path, tmp_path: Path, update_goldens: bool) -> None:
    play, flags, requires = _case(folder)
    for req in requires:
        name, _, wanted = req.partition("==")
        if version(name) != wanted:
            pytest.skip(f"golden pinned to {req}, installed {version(name)}")
    out = tmp_path / "out"
    result = build(play, out, engine=_engine(flags), cache_dir=tmp_path / "cache", jobs=2)
    text = (out / "timeline.json").read_text(encoding="utf-8")
    assert text == dumps(result.timeline)
    expected = folder / "expected.json"
    if update_goldens:
        expected.write_text(text, encoding="utf-8")
    assert expected.exists(), "run pytest --update-goldens to create it"
    assert text == expected.read_text(encoding="utf-8")
    # Every clip the timeline names is in the directory with the bytes it claims.
    tl = loads(text)
    for clip in tl.clips():
        data = (out / clip.path).read_bytes()
        assert hashlib.sha256(data).hexdigest() == clip.sha256
    assert sorted(p.name for p in (out / "clips").iterdir()) == sorted(
        Path(c.path).name for c in tl.clips()
    )
