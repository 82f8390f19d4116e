"""16-bit mono PCM helpers: read clips, convert their rate, place them into a mix."""

from __future__ import annotations

import audioop  # on Python 3.13+ from the audioop-lts backport
import io
import wave


def read_wav(data: bytes) -> tuple[bytes, int]:
    """PCM frames and sample rate of a 16-bit mono WAV clip."""
    with wave.open(io.BytesIO(data)) as w:
        if w.getsampwidth() != 2 or w.getnchannels() != 1:
            raise ValueError("clips must be 16-bit mono WAV")
        return w.readframes(w.getnframes()), w.getframerate()


def convert(pcm: bytes, rate: int, to_rate: int) -> bytes:
    if rate == to_rate:
        return pcm
    converted, _ = audioop.ratecv(pcm, 2, 1, rate, to_rate, None)
    return bytes(converted)


def mix_into(buf: bytearray, offset_frames: int, pcm: bytes) -> None:
    """Add `pcm` into `buf` starting at `offset_frames` (saturating), growing nothing."""
    start = offset_frames * 2
    if start >= len(buf) or not pcm:
        return
    end = min(len(buf), start + len(pcm))
    buf[start:end] = audioop.add(bytes(buf[start:end]), pcm[: end - start], 2)


def write_wav(path: str, frames: bytes, rate: int, channels: int = 1) -> None:
    with wave.open(path, "wb") as w:
        w.setnchannels(channels)
        w.setsampwidth(2)
        w.setframerate(rate)
        w.writeframes(frames)


def pan(mono: bytes, left: float, right: float) -> bytes:
    return bytes(audioop.tostereo(mono, 2, left, right))


def add(a: bytes, b: bytes) -> bytes:
    return bytes(audioop.add(a, b, 2))
