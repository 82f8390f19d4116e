"""Expand a gesture into per-joint tracks of absolute keyframes.

A track is a list of (time ms from the gesture's start, radians, ease into the point).
It starts at the pose the joint holds when the gesture begins, so the player can
interpolate it without knowing what came before.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scriptc.model import Gesture, Joint, Keyframe

Track = list[tuple[int, float, str]]

DEFAULT_SPEED = 1.0  # rad/s for the return home of a joint with no max_speed
MIN_RETURN_MS = 200


@dataclass(frozen=True, slots=True)
class Expanded:
    """A gesture laid out in time: its tracks, duration and the pose it leaves behind."""

    tracks: dict[str, Track]
    duration_ms: int
    end_pose: dict[str, float]
    frames: tuple[tuple[int, Keyframe], ...]


def _frames(g: Gesture) -> list[tuple[int, Keyframe]]:
    """Keyframes with their time from the gesture start, repeats unrolled."""
    out: list[tuple[int, Keyframe]] = [(kf.at_ms, kf) for kf in g.keyframes]
    if g.loop:
        base = g.keyframes[-1].at_ms if g.keyframes else 0
        period = g.loop[-1].at_ms
        for i in range(g.repeat):
            out.extend((base + i * period + kf.at_ms, kf) for kf in g.loop)
    elif g.repeat > 1 and g.keyframes:
        period = g.keyframes[-1].at_ms
        for i in range(1, g.repeat):
            out.extend((i * period + kf.at_ms, kf) for kf in g.keyframes)
    # A repeat that restarts at offset 0 lands on the previous cycle's last time;
    # keep times strictly increasing by dropping the duplicated instant.
    dedup: list[tuple[int, Keyframe]] = []
    for t, kf in out:
        if dedup and t <= dedup[-1][0]:
            t = dedup[-1][0] + 1
        dedup.append((t, kf))
    return dedup


def expand(g: Gesture, joints: dict[str, Joint], start_pose: dict[str, float]) -> Expanded:
    """Lay out `g` for a robot with `joints`, starting from `start_pose`."""
    frames = _frames(g)
    tracks: dict[str, Track] = {}
    for t, kf in frames:
        for target in kf.targets:
            if target.joint not in joints:
                continue
            track = tracks.setdefault(target.joint, [(0, start_pose[target.joint], "linear")])
            if t == 0:
                track[0] = (0, target.rad, "step")
            else:
                track.append((t, target.rad, kf.ease))
    end = frames[-1][0] if frames else 0
    end_pose = {j: tr[-1][1] for j, tr in tracks.items()}
    if g.then == "home" and tracks:
        ret = g.return_ms
        if ret is None:
            need = max(
                abs(end_pose[j] - joints[j].home) / (joints[j].max_speed or DEFAULT_SPEED)
                for j in tracks
            )
            ret = max(MIN_RETURN_MS, 10 * math.ceil(need * 1.5 * 100))
        for j, tr in tracks.items():
            if tr[-1][0] < end:  # hold the last target until the gesture's end, then return
                tr.append((end, tr[-1][1], "linear"))
            tr.append((end + ret, joints[j].home, "in-out"))
            end_pose[j] = joints[j].home
        end += ret
    return Expanded(tracks, end, end_pose, tuple(frames))
