"""A deterministic test voice: every word is a 300 ms tone burst (250 ms of tone, 50 ms
of silence) at 16 kHz, so durations and word times are known exactly without an engine.

Goldens and player tests use it; `wpm` is not supported, the rate is fixed on purpose.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Sequence

from scriptc import anchors
from scriptc.audio import wav_bytes
from scriptc.model import PollySettings, Voice
from scriptc.voices.base import OnDone, Synthesized, SynthJob, VoiceInfo

RATE = 16000
WORD_MS = 300
TONE_MS = 250


def _tone(freq: float) -> bytes:
    n = RATE * TONE_MS // 1000
    return b"".join(
        struct.pack("<h", int(8000 * math.sin(2 * math.pi * freq * i / RATE))) for i in range(n)
    )


class FixedBackend:
    name = "fixed"

    def identity(self) -> dict[str, str]:
        return {"engine": "fixed", "version": "1"}

    def job(
        self, cue: str, text: str, ssml: bool, voice: Voice | None, polly: PollySettings
    ) -> SynthJob:
        return SynthJob(cue, text, ssml, voice.id if voice else "tone", None)

    def synthesize(self, jobs: Sequence[SynthJob], *, workers: int, on_done: OnDone) -> None:
        silence = b"\x00\x00" * (RATE * (WORD_MS - TONE_MS) // 1000)
        for job in jobs:
            freq = 300 + (sum(job.voice.encode()) % 8) * 50
            tone = _tone(freq)
            ws = anchors.words(job.text)
            pcm = (tone + silence) * max(1, len(ws))
            words = tuple((w.start, w.end, i * WORD_MS) for i, w in enumerate(ws))
            marks = tuple(
                (name, WORD_MS * sum(1 for w in ws if w.start < job.text.find(f'"{name}"')))
                for name in anchors.marks(job.text)
            )
            on_done(job, Synthesized(wav_bytes(pcm, RATE), words, marks))

    def voices(self) -> list[VoiceInfo]:
        return [VoiceInfo("tone", "any", note="test voice: 300 ms tone per word")]
