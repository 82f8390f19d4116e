"""Voice backends by name, including a third-party one installed through an entry point."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from scriptc.build import build
from scriptc.voices import registry
from scriptc.voices.base import VoiceError

PLUGIN = """
from scriptc.voices.fixed import FixedBackend

class Tone2(FixedBackend):
    name = "tone2"

    def identity(self):
        return {"engine": "tone2", "version": "1"}
"""


@pytest.fixture
def plugin(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> str:
    """A real distribution on sys.path whose entry point registers the `tone2` engine."""
    site = tmp_path / "site"
    site.mkdir()
    (site / "tone2_voice.py").write_text(PLUGIN)
    info = site / "tone2_voice-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: tone2-voice\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text("[scriptc.voices]\ntone2 = tone2_voice:Tone2\n")
    monkeypatch.syspath_prepend(str(site))
    yield "tone2"
    sys.modules.pop("tone2_voice", None)


def test_builtin_names() -> None:
    assert {"espeak", "polly", "fixed"} <= set(registry.names())


def test_unknown_name_fails_with_a_suggestion() -> None:
    with pytest.raises(VoiceError, match="unknown voice engine 'espek'") as exc:
        registry.get("espek")
    assert exc.value.hint == "did you mean 'espeak'?"


def test_entry_point_backend_is_found_and_builds(plugin: str, tmp_path: Path) -> None:
    assert plugin in registry.names()
    backend = registry.get(plugin)
    assert backend.identity() == {"engine": "tone2", "version": "1"}
    play = tmp_path / "p.yaml"
    play.write_text("robots:\n  a: {}\nscenes:\n  - lines:\n      - a: Hello there.\n")
    result = build(play, tmp_path / "out", engine=plugin, cache_dir=tmp_path / "cache")
    assert result.timeline.engine == "tone2"
    assert result.timeline.robots["a"].audio[0].duration == 600
