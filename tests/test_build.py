"""The build stage end to end with the real embedded voice and the real cache."""

from __future__ import annotations

import json
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import ClassVar

import pytest
from typer.testing import CliRunner

from scriptc.build import build
from scriptc.cache import AudioCache
from scriptc.cli import app
from scriptc.diagnostics import ScriptcError
from scriptc.timeline import dumps, loads
from scriptc.voices import registry
from scriptc.voices.base import OnDone, SynthJob
from scriptc.voices.espeak import EspeakBackend

PLAYS = Path(__file__).resolve().parents[1] / "plays"
runner = CliRunner()


class CountingEspeak(EspeakBackend):
    """The real eSpeak backend, counting the lines it is asked to synthesise."""

    calls: ClassVar[list[str]] = []

    def synthesize(self, jobs: Sequence[SynthJob], *, workers: int, on_done: OnDone) -> None:
        CountingEspeak.calls.extend(j.cue for j in jobs)
        super().synthesize(jobs, workers=workers, on_done=on_done)


@pytest.fixture
def counting(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    CountingEspeak.calls = []
    monkeypatch.setitem(registry.BUILTIN, "espeak", f"{__name__}:CountingEspeak")
    return CountingEspeak.calls


def test_rebuild_is_byte_identical_and_synthesises_nothing(
    tmp_path: Path, counting: list[str]
) -> None:
    cache = tmp_path / "cache"
    first = build(PLAYS / "einstein.yaml", tmp_path / "a", cache_dir=cache)
    assert first.synthesized == len(counting) == 10
    counting.clear()
    second = build(PLAYS / "einstein.yaml", tmp_path / "a", cache_dir=cache)
    assert second.synthesized == 0 and counting == []
    third = build(PLAYS / "einstein.yaml", tmp_path / "b", cache_dir=cache)
    assert third.synthesized == 0 and counting == []
    a = (tmp_path / "a" / "timeline.json").read_bytes()
    assert a == (tmp_path / "b" / "timeline.json").read_bytes()
    # A cold build with an empty cache gives the same bytes: eSpeak output is deterministic.
    build(PLAYS / "einstein.yaml", tmp_path / "c", cache_dir=tmp_path / "cold")
    assert a == (tmp_path / "c" / "timeline.json").read_bytes()
    for clip in (tmp_path / "a" / "clips").iterdir():
        assert clip.read_bytes() == (tmp_path / "c" / "clips" / clip.name).read_bytes()


def test_timeline_is_canonical(tmp_path: Path) -> None:
    build(PLAYS / "einstein.yaml", tmp_path / "out", cache_dir=tmp_path / "cache")
    text = (tmp_path / "out" / "timeline.json").read_text(encoding="utf-8")
    data = json.loads(text)
    # Canonical: reading and writing it again gives the same bytes, keys sorted at every level.
    assert dumps(loads(text)) == text
    assert list(data) == sorted(data) and text.endswith("}\n")
    assert data["format"] == "scriptc.timeline/1"
    assert str(tmp_path) not in text and "/work" not in text
    assert set(data["robots"]) == {"einstein", "dim", "newton"}
    # Einstein's German voice: the clip header and the word timings come from eSpeak itself.
    hello = data["robots"]["einstein"]["audio"][0]
    assert hello["clip"]["sample_rate"] == 22050
    assert hello["duration"] == round(hello["clip"]["samples"] * 1000 / 22050)
    assert [w for _, w in hello["words"]][:3] == ["Good", "evening", "I"]
    times = [t for t, _ in hello["words"]]
    assert times == sorted(times) and times[-1] < hello["duration"]


def test_corrupt_cache_entries_are_misses(tmp_path: Path, counting: list[str]) -> None:
    cache = tmp_path / "cache"
    build(PLAYS / "einstein.yaml", tmp_path / "a", cache_dir=cache)
    metas = sorted((cache / "v1" / "meta").rglob("*.json"))
    blobs = sorted((cache / "v1" / "blobs").rglob("*.wav"))
    metas[0].write_text("{not json")  # garbage record
    metas[1].write_bytes(b"")  # empty record
    blobs[0].write_bytes(blobs[0].read_bytes()[:100])  # truncated blob
    counting.clear()
    shutil.rmtree(tmp_path / "a")  # no clips in the output: every hit is verified
    result = build(PLAYS / "einstein.yaml", tmp_path / "a", cache_dir=cache)
    assert 2 <= result.synthesized <= 3 and len(counting) == result.synthesized
    # A blob with the right size but flipped bytes is caught by its hash.
    blob = sorted((cache / "v1" / "blobs").rglob("*.wav"))[-1]
    data = bytearray(blob.read_bytes())
    data[-1] ^= 0xFF
    blob.write_bytes(bytes(data))
    shutil.rmtree(tmp_path / "a")
    counting.clear()
    result = build(PLAYS / "einstein.yaml", tmp_path / "a", cache_dir=cache)
    assert result.synthesized >= 1
    assert (
        AudioCache(cache).get(next(iter((cache / "v1" / "meta").rglob("*.json"))).stem) is not None
    )


def test_failed_build_writes_nothing(tmp_path: Path) -> None:
    play = tmp_path / "bad.yaml"
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\n"
        "scenes:\n  - scene: s\n    lines:\n      - a: One two three four five six.\n"
        "      - a: Too soon.\n        at: 1s\n"
    )
    with pytest.raises(ScriptcError) as exc:
        build(play, tmp_path / "out", cache_dir=tmp_path / "cache")
    assert [d.code for d in exc.value.diagnostics] == ["E040"]
    assert not (tmp_path / "out").exists()


def test_failed_build_keeps_the_previous_output(tmp_path: Path) -> None:
    play = tmp_path / "p.yaml"
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\nscenes:\n  - lines:\n      - a: Hello.\n"
    )
    build(play, tmp_path / "out", cache_dir=tmp_path / "cache")
    before = (tmp_path / "out" / "timeline.json").read_bytes()
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\nscenes:\n  - lines:\n      - b: Hello.\n"
    )
    with pytest.raises(ScriptcError):
        build(play, tmp_path / "out", cache_dir=tmp_path / "cache")
    assert (tmp_path / "out" / "timeline.json").read_bytes() == before


def test_build_cli_reports_errors_with_positions(in_tmp: Path) -> None:
    play = in_tmp / "p.yaml"
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\nscenes:\n  - lines:\n      - a: Hi.\n"
        "        gesture: wave\n"
    )
    result = runner.invoke(app, ["build", "--format", "plain", str(play)])
    assert result.exit_code == 1
    assert "p.yaml:6:18: error E021 unknown gesture 'wave'" in result.stderr
    assert not (in_tmp / "build").exists()


def test_build_cli_quiet_and_jobs(in_tmp: Path) -> None:
    shutil.copytree(PLAYS, in_tmp / "plays")
    result = runner.invoke(app, ["build", "-q", "--jobs", "3", "plays/einstein.yaml"])
    assert result.exit_code == 0, result.output
    assert result.output == ""
    assert (in_tmp / "build" / "einstein" / "timeline.json").exists()
    shown = runner.invoke(app, ["show", "build/einstein"])
    assert shown.exit_code == 0 and "Good evening" in shown.stdout and "wave" in shown.stdout


def test_stale_clips_are_removed(tmp_path: Path) -> None:
    play = tmp_path / "p.yaml"
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\nscenes:\n  - lines:\n      - a: Hello.\n"
    )
    build(play, tmp_path / "out", cache_dir=tmp_path / "cache")
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\nscenes:\n  - lines:\n      - a: Goodbye.\n"
    )
    result = build(play, tmp_path / "out", cache_dir=tmp_path / "cache")
    clips = list((tmp_path / "out" / "clips").iterdir())
    assert [c.name for c in clips] == [Path(c.path).name for c in result.timeline.clips()]


def test_unknown_engine_is_a_clear_error(tmp_path: Path) -> None:
    with pytest.raises(ScriptcError, match="unknown voice engine 'klingon'"):
        build(PLAYS / "einstein.yaml", tmp_path / "o", engine="klingon", cache_dir=tmp_path / "c")
