"""E031 joint-speed: no keyframe may ask a joint to move faster than its `max_speed`.

The speed of a segment is its distance over its time, times the peak slope of its
easing (1.5 for `in-out`, 2 for `in`/`out`). A too-fast segment inside a gesture is
an error at that keyframe. The first segment starts from wherever the joint is when
the gesture begins, which depends on the play, so a too-fast start is a warning
(W031) at the cue: the player will clamp the speed and arrive late.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity
from scriptc.easing import PEAK_SLOPE

CODE = "E031"
SLUG = "joint-speed"
TIMING = True  # needs the layout


def check(ctx: Context) -> Iterator[Diagnostic]:
    if ctx.layout is None:
        return
    for pm in ctx.layout.motions:
        robot = ctx.play.robots.get(pm.robot)
        if robot is None or pm.expanded is None:
            continue
        by_time = {t: kf for t, kf in pm.expanded.frames}
        for joint, track in pm.expanded.tracks.items():
            limit = robot.joints[joint].max_speed
            if limit is None:
                continue
            for i, ((t0, p0, _), (t1, p1, ease)) in enumerate(itertools.pairwise(track)):
                if ease == "step" or p0 == p1:
                    continue
                dt = max(t1 - t0, 1) / 1000.0
                speed = abs(p1 - p0) / dt * PEAK_SLOPE[ease]
                if speed <= limit * 1.0001:
                    continue
                msg = (
                    f"{joint} would move at {math.degrees(speed):.0f}deg/s, over its "
                    f"{math.degrees(limit):.0f}deg/s limit"
                )
                need = math.ceil(abs(p1 - p0) * PEAK_SLOPE[ease] / limit * 1000)
                hint = f"allow at least {need}ms for this move"
                kf = by_time.get(t1)
                if i == 0 or kf is None:
                    yield Diagnostic(
                        pm.span,
                        Severity.WARNING,
                        "W031",
                        f"{msg} at the start of {pm.gesture!r}",
                        hint,
                    )
                else:
                    yield Diagnostic(
                        kf.span, Severity.ERROR, CODE, f"{msg} in {pm.gesture!r}", hint
                    )
