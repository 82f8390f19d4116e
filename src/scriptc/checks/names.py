"""E020–E022 names: every robot, gesture and joint a cue names must exist.

A gesture cue names a robot (the speaker unless `robot:` says otherwise) and a
gesture from the library; the gesture may only move joints that robot has. A
joint that no robot has at all is reported where the gesture defines it, with
the closest joint names as a hint.
"""

from __future__ import annotations

from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity, Span, did_you_mean, known
from scriptc.model import GestureCue, Line, Motion

CODE = "E020"
SLUG = "names"
TIMING = False  # reads the play alone


def check(ctx: Context) -> Iterator[Diagnostic]:
    play = ctx.play
    all_joints = {j for r in play.robots.values() for j in r.joints}
    for g in play.gestures.values():
        for kf in (*g.keyframes, *g.loop):
            for t in kf.targets:
                if t.joint not in all_joints:
                    yield Diagnostic(
                        t.span,
                        Severity.ERROR,
                        "E022",
                        f"gesture {g.name!r} moves unknown joint {t.joint!r}",
                        did_you_mean(t.joint, all_joints) or known(all_joints),
                    )
    for scene in play.scenes:
        for item in scene.items:
            uses: list[tuple[str, str, Span]] = []
            if isinstance(item, Line):
                uses = [(gc.robot, gc.gesture, gc.span) for gc in item.gestures]
                for gc in item.gestures:
                    yield from _robot(ctx, gc)
            elif isinstance(item, Motion):
                uses = [(item.robot, item.gesture, item.span)]
            for robot_name, gesture_name, span in uses:
                gesture = play.gestures.get(gesture_name)
                if gesture is None:
                    yield Diagnostic(
                        span,
                        Severity.ERROR,
                        "E021",
                        f"unknown gesture {gesture_name!r}",
                        did_you_mean(gesture_name, play.gestures) or known(play.gestures),
                    )
                    continue
                robot = play.robots.get(robot_name)
                if robot is None:
                    continue
                missing = [j for j in gesture.joints() if j not in robot.joints and j in all_joints]
                if missing:
                    yield Diagnostic(
                        span,
                        Severity.ERROR,
                        "E022",
                        f"{robot_name} has no joint {missing[0]!r} for gesture {gesture_name!r}",
                        known(robot.joints) if robot.joints else f"give {robot_name} `joints:`",
                    )


def _robot(ctx: Context, gc: GestureCue) -> Iterator[Diagnostic]:
    if gc.robot not in ctx.play.robots:
        yield Diagnostic(
            gc.span,
            Severity.ERROR,
            "E020",
            f"unknown robot {gc.robot!r}",
            did_you_mean(gc.robot, ctx.play.robots) or known(ctx.play.robots),
        )
