"""E041 joint-conflict: two gestures may not drive the same joint at the same time.

Gestures of one robot that overlap in time must move different joints. The later
cue is reported, naming the earlier one.
"""

from __future__ import annotations

from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity
from scriptc.layout import PlacedMotion

CODE = "E041"
SLUG = "joint-conflict"
TIMING = True  # needs the layout


def check(ctx: Context) -> Iterator[Diagnostic]:
    if ctx.layout is None:
        return
    by_robot: dict[str, list[PlacedMotion]] = {}
    for pm in ctx.layout.motions:
        if pm.expanded is not None:
            by_robot.setdefault(pm.robot, []).append(pm)
    for robot, motions in by_robot.items():
        motions.sort(key=lambda m: (m.start, m.order))
        for i, b in enumerate(motions):
            for a in motions[:i]:
                if a.end <= b.start:
                    continue
                assert a.expanded is not None and b.expanded is not None
                shared = sorted(set(a.expanded.tracks) & set(b.expanded.tracks))
                if not shared:
                    continue
                sev = Severity.ERROR if ctx.layout.exact or a.start == b.start else Severity.WARNING
                yield Diagnostic(
                    b.span,
                    sev,
                    CODE if sev is Severity.ERROR else "W041",
                    f"{robot}'s {b.gesture!r} drives {', '.join(shared)} while "
                    f"{a.gesture!r} ({a.cue}) still does",
                    f"they overlap by {a.end - b.start}ms; start it later or use "
                    "gestures on different joints",
                )
                break
