"""E030 joint-limits: every keyframe target must lie within the joint's min and max.

Checked for each robot that performs the gesture, at the keyframe that sets the
target, so a gesture shared by robots with different arms is checked per arm.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity

CODE = "E030"
SLUG = "joint-limits"
TIMING = True  # needs the layout


def check(ctx: Context) -> Iterator[Diagnostic]:
    if ctx.layout is None:
        return
    seen: set[tuple[str, str]] = set()
    for pm in ctx.layout.motions:
        if (pm.robot, pm.gesture) in seen:
            continue
        seen.add((pm.robot, pm.gesture))
        robot = ctx.play.robots.get(pm.robot)
        gesture = ctx.play.gestures.get(pm.gesture)
        if robot is None or gesture is None:
            continue
        for kf in (*gesture.keyframes, *gesture.loop):
            for t in kf.targets:
                j = robot.joints.get(t.joint)
                if j is None or j.min - 1e-9 <= t.rad <= j.max + 1e-9:
                    continue
                yield Diagnostic(
                    t.span,
                    Severity.ERROR,
                    CODE,
                    f"{t.joint} target {math.degrees(t.rad):.1f}deg is outside {pm.robot}'s limits",
                    f"limits are {math.degrees(j.min):.1f}deg to {math.degrees(j.max):.1f}deg",
                )
