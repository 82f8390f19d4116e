"""What one robot does, read from a built timeline: its clips, motions, joints, and where
a rehearsal starts (`--from CUE` or `--from SCENE`)."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path

from scriptc import timeline as tl
from scriptc.diagnostics import did_you_mean
from scriptc.easing import position_at


class PlanError(Exception):
    """The timeline or its clips cannot be played; the message says why."""


@dataclass(frozen=True, slots=True)
class JointSpec:
    name: str
    id: int
    min: float
    max: float
    home: float
    max_speed: float | None


@dataclass(slots=True)
class RobotPlan:
    name: str
    bus: dict[str, object] | None
    joints: dict[str, JointSpec]
    audio: list[tl.AudioEvent] = field(default_factory=list)
    motion: list[tl.MotionEvent] = field(default_factory=list)

    @property
    def home(self) -> dict[str, float]:
        return {j.name: j.home for j in self.joints.values()}

    def pose_at(self, t_ms: float) -> dict[str, float]:
        """Where every joint is at timeline time `t_ms`: the gesture driving it, or where the
        last one left it, or home."""
        pose = self.home
        for m in self.motion:
            if m.start > t_ms:
                break
            for joint, track in m.tracks.items():
                if joint in pose:
                    pose[joint] = position_at(track, t_ms)
        return pose

    def end_ms(self) -> int:
        ends = [a.start + a.duration for a in self.audio] + [
            m.start + m.duration for m in self.motion
        ]
        return max(ends, default=0)


def load(build_dir: Path) -> tl.Timeline:
    path = build_dir / "timeline.json" if build_dir.is_dir() else build_dir
    try:
        return tl.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise PlanError(f"cannot read {path}: {exc.strerror or exc}") from None
    except tl.TimelineError as exc:
        raise PlanError(str(exc)) from None


def robots(timeline: tl.Timeline, names: list[str]) -> list[RobotPlan]:
    """Plans for the named robots (`all` for every robot)."""
    wanted = sorted(timeline.robots) if names == ["all"] else names
    plans = []
    for name in wanted:
        part = timeline.robots.get(name)
        if part is None:
            hint = did_you_mean(name, timeline.robots) or "robots: " + ", ".join(
                sorted(timeline.robots)
            )
            raise PlanError(f"the timeline has no robot {name!r} ({hint})")
        hw = part.hardware
        joints = {
            j: JointSpec(
                j,
                int(v["id"]),
                float(v["min"]),
                float(v["max"]),
                float(v["home"]),
                None if v.get("max_speed") is None else float(v["max_speed"]),
            )
            for j, v in hw.get("joints", {}).items()
        }
        plans.append(RobotPlan(name, hw.get("bus"), joints, list(part.audio), list(part.motion)))
    return plans


def start_of(timeline: tl.Timeline, cue_or_scene: str | None) -> int:
    """Timeline time where a rehearsal from a cue or scene starts (0 for the whole show)."""
    if cue_or_scene is None:
        return 0
    for c in timeline.cues:
        if c.id == cue_or_scene:
            return c.start
    for s in timeline.scenes:
        if s.id == cue_or_scene:
            return s.start
    names = [c.id for c in timeline.cues] + [s.id for s in timeline.scenes]
    hint = did_you_mean(cue_or_scene, names) or "see `scriptc show` for the cue ids"
    raise PlanError(f"no cue or scene {cue_or_scene!r} ({hint})")


def read_clips(build_dir: Path, plans: list[RobotPlan], from_ms: int) -> dict[str, bytes]:
    """Every clip these robots play from `from_ms` on, verified against its SHA-256."""
    base = build_dir if build_dir.is_dir() else build_dir.parent
    clips: dict[str, bytes] = {}
    for plan in plans:
        for a in plan.audio:
            if a.start < from_ms or a.clip.sha256 in clips:
                continue
            path = base / a.clip.path
            try:
                data = path.read_bytes()
            except OSError:
                raise PlanError(
                    f"clip {a.clip.path} for {plan.name}'s {a.cue} is missing; "
                    "copy the whole build directory"
                ) from None
            if hashlib.sha256(data).hexdigest() != a.clip.sha256:
                raise PlanError(
                    f"clip {a.clip.path} is damaged (hash mismatch); rebuild or recopy it"
                )
            clips[a.clip.sha256] = data
    return clips


def glide_ms(
    joints: dict[str, JointSpec],
    frm: dict[str, float],
    to: dict[str, float],
    default_speed: float = 0.5,
) -> int:
    """Time to move every joint from `frm` to `to` at half its top speed (ease in-out)."""
    need = 0.0
    for name in to:
        j = joints[name]
        speed = (j.max_speed or 2 * default_speed) / 2
        need = max(need, abs(to[name] - frm.get(name, to[name])) * 1.5 / speed)
    return max(200, math.ceil(need * 1000 / 10) * 10)
