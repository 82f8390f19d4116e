"""`scriptc render`: the whole show as one WAV, every robot on its own channel or panned."""

from __future__ import annotations

import math
from array import array
from pathlib import Path

from scriptc.player import pcm as pcmlib
from scriptc.player import plan as planlib


def render(build_dir: Path, out: Path, *, mode: str = "channels") -> tuple[int, int, int]:
    """Write the mixdown; return (channels, sample rate, frames)."""
    timeline = planlib.load(build_dir)
    plans = planlib.robots(timeline, ["all"])
    base = build_dir if build_dir.is_dir() else build_dir.parent
    clips = planlib.read_clips(base, plans, 0)
    decoded = {sha: pcmlib.read_wav(data) for sha, data in clips.items()}
    rate = max((r for _, r in decoded.values()), default=22050)
    frames = math.ceil(timeline.duration * rate / 1000) + 1
    tracks = []
    for plan in plans:
        buf = bytearray(frames * 2)
        for a in plan.audio:
            pcm, r = decoded[a.clip.sha256]
            pcmlib.mix_into(buf, round(a.start * rate / 1000), pcmlib.convert(pcm, r, rate))
        tracks.append(bytes(buf))
    if mode == "pan":
        mix = bytes(frames * 4)
        n = len(tracks)
        for i, track in enumerate(tracks):
            p = 0.5 if n == 1 else i / (n - 1)
            mix = pcmlib.add(
                mix, pcmlib.pan(track, math.cos(p * math.pi / 2), math.sin(p * math.pi / 2))
            )
        pcmlib.write_wav(str(out), mix, rate, 2)
        return 2, rate, frames
    interleaved = array("h", bytes(frames * 2 * len(tracks)))
    for ch, track in enumerate(tracks):
        interleaved[ch :: len(tracks)] = array("h", track)
    pcmlib.write_wav(str(out), interleaved.tobytes(), rate, len(tracks))
    return len(tracks), rate, frames
