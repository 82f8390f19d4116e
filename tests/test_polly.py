"""The Polly backend against the real boto3 client, with botocore's Stubber at the wire."""

from __future__ import annotations

import io
import json
import struct
from pathlib import Path
from typing import Any

import boto3
import pytest
from botocore.config import Config
from botocore.response import StreamingBody
from botocore.stub import Stubber

from scriptc.audio import measure
from scriptc.build import build
from scriptc.diagnostics import ScriptcError, Span
from scriptc.model import PollySettings, Voice
from scriptc.voices.base import Synthesized, SynthJob, VoiceError
from scriptc.voices.polly import PollyBackend, RateLimiter

SPAN = Span("t.yaml", 1, 1)


def _client(**creds: str) -> Any:
    session = boto3.session.Session(region_name="eu-west-1", **creds)
    return session.client("polly", config=Config(retries={"max_attempts": 1, "mode": "standard"}))


@pytest.fixture
def stubbed() -> tuple[Any, Stubber]:
    client = _client(aws_access_key_id="testing", aws_secret_access_key="testing")
    with Stubber(client) as stub:
        yield client, stub
        stub.assert_no_pending_responses()


def _pcm(ms: int, rate: int = 16000) -> bytes:
    return struct.pack("<h", 1000) * (rate * ms // 1000)


def _stream(data: bytes) -> StreamingBody:
    return StreamingBody(io.BytesIO(data), len(data))


def _marks(*marks: dict[str, Any]) -> bytes:
    return "\n".join(json.dumps(m) for m in marks).encode() + b"\n"


def _job(text: str, voice: str = "Matthew", ssml: bool = False, **polly: Any) -> SynthJob:
    settings = PollySettings(**polly)
    return PollyBackend().job("scene/1", text, ssml, Voice("polly", voice, SPAN, "en-US"), settings)


def _run(backend: PollyBackend, *jobs: SynthJob) -> dict[str, Synthesized]:
    out: dict[str, Synthesized] = {}
    backend.synthesize(list(jobs), workers=1, on_done=lambda j, r: out.__setitem__(j.cue, r))
    return out


def test_request_shape_and_word_marks(stubbed: tuple[Any, Stubber]) -> None:
    client, stub = stubbed
    text = "Grüße, Herr Newton!"
    job = _job(text, engine="neural", lexicons=("physics",))
    base = {
        "Engine": "neural",
        "VoiceId": "Matthew",
        "Text": text,
        "TextType": "text",
        "LanguageCode": "en-US",
        "LexiconNames": ["physics"],
    }
    stub.add_response(
        "synthesize_speech",
        {"AudioStream": _stream(_pcm(1200)), "ContentType": "audio/pcm", "RequestCharacters": 19},
        {**base, "OutputFormat": "pcm", "SampleRate": "16000"},
    )
    # Byte offsets: "Grüße" is 7 bytes in UTF-8, so "Herr" starts at byte 9, character 7.
    marks = _marks(
        {"time": 0, "type": "sentence", "start": 0, "end": 22, "value": text},
        {"time": 6, "type": "word", "start": 0, "end": 7, "value": "Grüße"},
        {"time": 6, "type": "viseme", "value": "k"},
        {"time": 480, "type": "word", "start": 9, "end": 13, "value": "Herr"},
        {"time": 700, "type": "word", "start": 14, "end": 20, "value": "Newton"},
    )
    stub.add_response(
        "synthesize_speech",
        {"AudioStream": _stream(marks), "ContentType": "application/x-json-stream"},
        {**base, "OutputFormat": "json", "SpeechMarkTypes": ["word", "sentence", "viseme"]},
    )
    out = _run(PollyBackend(client), job)["scene/1"]
    assert measure(out.wav).sample_rate == 16000
    assert measure(out.wav).duration_ms == 1200
    assert [(text[a:b], t) for a, b, t in out.words] == [
        ("Grüße", 6),
        ("Herr", 480),
        ("Newton", 700),
    ]
    assert out.extra["visemes"] == [[6, "k"]]


def test_ssml_asks_for_ssml_marks(stubbed: tuple[Any, Stubber]) -> None:
    client, stub = stubbed
    text = '<speak>Wave <mark name="now"/> now.</speak>'
    base = {"Engine": "standard", "VoiceId": "Hans", "Text": text, "TextType": "ssml"}
    stub.add_response(
        "synthesize_speech",
        {"AudioStream": _stream(_pcm(500))},
        {**base, "OutputFormat": "pcm", "SampleRate": "16000"},
    )
    stub.add_response(
        "synthesize_speech",
        {
            "AudioStream": _stream(
                _marks({"time": 310, "type": "ssml", "start": 12, "end": 30, "value": "now"})
            )
        },
        {**base, "OutputFormat": "json", "SpeechMarkTypes": ["word", "sentence", "viseme", "ssml"]},
    )
    job = PollyBackend().job("c", text, True, Voice("polly", "Hans", SPAN), PollySettings())
    out = _run(PollyBackend(client), job)["c"]
    assert out.marks == (("now", 310),)


def test_throttling_is_retried_with_exponential_backoff(stubbed: tuple[Any, Stubber]) -> None:
    client, stub = stubbed
    slept: list[float] = []
    for _ in range(3):
        stub.add_client_error(
            "synthesize_speech",
            service_error_code="ThrottlingException",
            service_message="Rate exceeded",
            http_status_code=400,
        )
    stub.add_response("synthesize_speech", {"AudioStream": _stream(_pcm(100))})
    stub.add_client_error(
        "synthesize_speech", service_error_code="ServiceFailureException", http_status_code=500
    )
    stub.add_response("synthesize_speech", {"AudioStream": _stream(b"")})
    backend = PollyBackend(client, sleep=slept.append, base_delay=0.25)
    out = _run(backend, _job("Hello."))
    assert measure(out["scene/1"].wav).duration_ms == 100
    backoff = [s for s in slept if s >= 0.2]
    assert backoff == [0.25, 0.5, 1.0, 0.25]


def test_throttling_that_never_ends_is_a_clear_error(stubbed: tuple[Any, Stubber]) -> None:
    client, stub = stubbed
    for _ in range(3):
        stub.add_client_error(
            "synthesize_speech", service_error_code="ThrottlingException", http_status_code=400
        )
    backend = PollyBackend(client, sleep=lambda s: None, max_attempts=3)
    with pytest.raises(VoiceError, match="kept throttling after 3 tries") as exc:
        _run(backend, _job("Hello."))
    assert exc.value.cue == "scene/1" and "jobs" in (exc.value.hint or "")


@pytest.mark.parametrize(
    ("code", "message", "expected"),
    [
        (
            "EngineNotSupportedException",
            "nope",
            "voice Matthew does not support the standard engine",
        ),
        ("InvalidSsmlException", "bad tag", "Polly rejected the SSML: bad tag"),
        ("LexiconNotFoundException", "physics", "a lexicon was not found"),
        ("ValidationException", "Value 'Mathew' at 'voiceId' failed", "Polly does not know voice"),
        ("UnrecognizedClientException", "bad token", "credentials were rejected"),
    ],
)
def test_service_errors_are_explained(
    stubbed: tuple[Any, Stubber], code: str, message: str, expected: str
) -> None:
    client, stub = stubbed
    stub.add_client_error(
        "synthesize_speech", service_error_code=code, service_message=message, http_status_code=400
    )
    with pytest.raises(VoiceError, match=expected):
        _run(PollyBackend(client), _job("Hello."))


def test_unknown_voice_fails_before_any_request(stubbed: tuple[Any, Stubber]) -> None:
    client, _ = stubbed
    with pytest.raises(VoiceError, match="does not know voice 'Mathew'"):
        _run(PollyBackend(client), _job("Hello.", voice="Mathew"))


def test_missing_credentials_is_a_clear_error() -> None:
    """A real client with an empty credential chain: botocore refuses before any network."""
    with pytest.raises(VoiceError, match="no AWS credentials found") as exc:
        _run(PollyBackend(_client(), sleep=lambda s: None), _job("Hello."))
    assert "AWS_PROFILE" in (exc.value.hint or "")


def test_missing_region_is_a_clear_error() -> None:
    with pytest.raises(VoiceError, match="no AWS region"):
        PollyBackend().client()


def test_unreadable_compressed_audio_is_a_clear_error(stubbed: tuple[Any, Stubber]) -> None:
    client, stub = stubbed
    stub.add_response("synthesize_speech", {"AudioStream": _stream(b"not an mp3 at all")})
    stub.add_response("synthesize_speech", {"AudioStream": _stream(b"")})
    with pytest.raises(VoiceError, match="cannot decode Polly's mp3"):
        _run(PollyBackend(client), _job("Hello.", format="mp3", sample_rate=24000))


DATA = Path(__file__).parent / "data"


@pytest.mark.parametrize(
    ("fmt", "name", "samples"),
    [
        ("mp3", "tone-600ms-24k.mp3", 15552),  # 600 ms plus the MP3 encoder's padding
        ("ogg_vorbis", "tone-600ms-24k.ogg", 14400),
    ],
)
def test_compressed_audio_is_decoded_at_its_own_rate(
    stubbed: tuple[Any, Stubber], fmt: str, name: str, samples: int
) -> None:
    client, stub = stubbed
    base = {
        "Engine": "standard",
        "VoiceId": "Matthew",
        "Text": "Hello.",
        "TextType": "text",
        "LanguageCode": "en-US",
    }
    stub.add_response(
        "synthesize_speech",
        {"AudioStream": _stream((DATA / name).read_bytes())},
        {**base, "OutputFormat": fmt, "SampleRate": "24000"},
    )
    stub.add_response("synthesize_speech", {"AudioStream": _stream(b"")})
    out = _run(PollyBackend(client), _job("Hello.", format=fmt, sample_rate=24000))["scene/1"]
    measured = measure(out.wav)
    assert (measured.sample_rate, measured.samples) == (24000, samples)


def test_voices_are_listed_across_pages(stubbed: tuple[Any, Stubber]) -> None:
    client, stub = stubbed
    stub.add_response(
        "describe_voices",
        {
            "Voices": [
                {
                    "Id": "Matthew",
                    "LanguageCode": "en-US",
                    "Gender": "Male",
                    "SupportedEngines": ["neural"],
                }
            ],
            "NextToken": "p2",
        },
        {},
    )
    stub.add_response(
        "describe_voices",
        {
            "Voices": [
                {
                    "Id": "Hans",
                    "LanguageCode": "de-DE",
                    "Gender": "Male",
                    "SupportedEngines": ["standard"],
                }
            ]
        },
        {"NextToken": "p2"},
    )
    voices = PollyBackend(client).voices()
    assert [(v.id, v.language, v.note) for v in voices] == [
        ("Hans", "de-DE", "standard"),
        ("Matthew", "en-US", "neural"),
    ]


def test_voices_fall_back_to_the_offline_list_without_credentials() -> None:
    voices = PollyBackend(_client()).voices()
    assert "Matthew" in {v.id for v in voices} and "offline" in voices[0].note


def test_rate_limiter_spaces_requests() -> None:
    now = [100.0]
    slept: list[float] = []

    def sleep(s: float) -> None:
        slept.append(round(s, 6))
        now[0] += s

    limiter = RateLimiter(8.0, clock=lambda: now[0], sleep=sleep)
    for _ in range(4):
        limiter.acquire()
    assert slept == [0.125, 0.125, 0.125]


def test_build_with_polly_end_to_end(
    stubbed: tuple[Any, Stubber], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    client, stub = stubbed
    monkeypatch.setattr(PollyBackend, "client", lambda self: client)
    play = tmp_path / "p.yaml"
    play.write_text(
        "defaults: {engine: polly, polly: {region: eu-west-1}}\n"
        "robots:\n  dim: {voice: {polly: Matthew}}\n"
        "scenes:\n  - lines:\n      - dim: Thank you.\n      - dim: Goodbye.\n"
    )
    for ms in (700, 900):
        stub.add_response("synthesize_speech", {"AudioStream": _stream(_pcm(ms))})
        stub.add_response(
            "synthesize_speech",
            {
                "AudioStream": _stream(
                    _marks({"time": 0, "type": "word", "start": 0, "end": 4, "value": "x"})
                )
            },
        )
    result = build(play, tmp_path / "out", cache_dir=tmp_path / "cache", jobs=1)
    audio = result.timeline.robots["dim"].audio
    assert [(a.start, a.duration) for a in audio] == [(0, 700), (950, 900)]
    assert result.timeline.engine == "polly"
    # Nothing changed: the rebuild is served from the cache, with no request at all.
    again = build(play, tmp_path / "out", cache_dir=tmp_path / "cache", jobs=1)
    assert again.synthesized == 0


def test_build_without_a_polly_voice_points_at_the_line(tmp_path: Path) -> None:
    play = tmp_path / "p.yaml"
    play.write_text(
        "robots:\n  dim: {voice: {espeak: en-us}}\nscenes:\n  - lines:\n      - dim: Hi.\n"
    )
    with pytest.raises(ScriptcError) as exc:
        build(play, tmp_path / "out", engine="polly", cache_dir=tmp_path / "cache")
    d = exc.value.diagnostics[0]
    assert (d.span.line, d.code) == (5, "E080") and "no Polly voice" in d.message
