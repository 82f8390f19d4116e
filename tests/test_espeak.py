"""The embedded eSpeak NG voice, called for real through ctypes."""

from __future__ import annotations

import hashlib

import pytest

from scriptc.audio import measure
from scriptc.diagnostics import Span
from scriptc.model import PollySettings, Voice
from scriptc.voices import catalog
from scriptc.voices.base import Synthesized, SynthJob, VoiceError
from scriptc.voices.espeak import EspeakBackend

SPAN = Span("t.yaml", 1, 1)


def _run(*jobs: SynthJob, workers: int = 2) -> dict[str, Synthesized]:
    out: dict[str, Synthesized] = {}
    EspeakBackend().synthesize(
        list(jobs), workers=workers, on_done=lambda j, r: out.__setitem__(j.cue, r)
    )
    return out


def _job(cue: str, text: str, voice: str = "en-us", ssml: bool = False) -> SynthJob:
    return EspeakBackend().job(cue, text, ssml, Voice("espeak", voice, SPAN), PollySettings())


def test_same_line_gives_the_same_bytes_whatever_came_before() -> None:
    text = "Good evening. I am Albert Einstein, and time is relative!"
    out = _run(
        _job("a", text, "de"),
        _job("b", "Something else first.", "de"),
        _job("c", text, "de"),
        workers=1,
    )
    assert hashlib.sha256(out["a"].wav).digest() == hashlib.sha256(out["c"].wav).digest()
    assert out["a"].words == out["c"].words


def test_word_events_point_at_the_words_of_the_text() -> None:
    text = "Schrödinger's cat naps, über alles."
    out = _run(_job("w", text))["w"]
    spoken = [text[a:b] for a, b, _ in out.words]
    # Positions are characters, not bytes: every word after the umlauts still lines up.
    assert spoken == ["Schrödinger", "cat", "naps", "über", "alles"]
    times = [t for _, _, t in out.words]
    assert times == sorted(times) and times[0] >= 0
    assert times[-1] < measure(out.wav).duration_ms


def test_ssml_marks_and_breaks() -> None:
    text = '<speak>Hello <mark name="here"/> world. <break time="500ms"/> Again.</speak>'
    plain = _run(_job("p", "Hello world. Again."))["p"]
    marked = _run(_job("m", text, ssml=True))["m"]
    assert [name for name, _ in marked.marks] == ["here"]
    assert 0 < marked.marks[0][1] < measure(marked.wav).duration_ms
    assert measure(marked.wav).duration_ms >= measure(plain.wav).duration_ms + 300


def test_rate_option_changes_the_audio_and_the_job() -> None:
    fast = EspeakBackend().job(
        "f",
        "A quick test of speed.",
        False,
        Voice("espeak", "en-us", SPAN, options=(("rate", 300),)),
        PollySettings(),
    )
    assert fast.setting("rate") == 300
    out = _run(fast, _job("n", "A quick test of speed."))
    assert measure(out["f"].wav).duration_ms < measure(out["n"].wav).duration_ms * 0.8


def test_unknown_voice_is_a_clear_error() -> None:
    with pytest.raises(VoiceError, match="no language voice 'klingon'"):
        _run(_job("x", "Hi.", "klingon"))


def test_language_codes_resolve_to_voice_files() -> None:
    assert catalog.espeak_resolve("en-gb") == "en"
    assert catalog.espeak_resolve("en-us+m3") == "en-us+m3"
    assert catalog.espeak_resolve("de") == "de"
    assert catalog.espeak_resolve("xx-nowhere") is None
    assert catalog.espeak_resolve("en-us+nosuchvariant") is None


def test_voices_lists_languages() -> None:
    ids = {v.id for v in EspeakBackend().voices()}
    assert {"de", "en-us", "en-gb"} <= ids
