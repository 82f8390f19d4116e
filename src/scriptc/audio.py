"""Clip bytes: build 16-bit mono WAV files and measure them with pydub."""

from __future__ import annotations

import io
import warnings
import wave
from dataclasses import dataclass


def wav_bytes(pcm: bytes, sample_rate: int) -> bytes:
    """Wrap little-endian 16-bit mono PCM in a WAV container."""
    buf = io.BytesIO()
    with wave.open(buf, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(sample_rate)
        w.writeframes(pcm)
    return buf.getvalue()


@dataclass(frozen=True, slots=True)
class Measured:
    sample_rate: int
    samples: int

    @property
    def duration_ms(self) -> int:
        return round(self.samples * 1000 / self.sample_rate)


def measure(wav: bytes) -> Measured:
    """Measure a WAV clip's exact length from its audio with pydub."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # pydub warns when ffmpeg is absent
        from pydub import AudioSegment

    seg = AudioSegment.from_wav(io.BytesIO(wav))
    return Measured(int(seg.frame_rate), int(seg.frame_count()))


def decode_compressed(data: bytes, fmt: str) -> tuple[bytes, int]:
    """Decode mp3 or ogg_vorbis bytes to 16-bit mono PCM at their own sample rate (miniaudio).

    `miniaudio.decode` resamples to 44.1 kHz unless told the rate, so read it first.
    """
    import miniaudio

    info = miniaudio.mp3_get_info(data) if fmt == "mp3" else miniaudio.vorbis_get_info(data)
    decoded = miniaudio.decode(
        data,
        output_format=miniaudio.SampleFormat.SIGNED16,
        nchannels=1,
        sample_rate=info.sample_rate,
    )
    return bytes(decoded.samples.tobytes()), int(decoded.sample_rate)
