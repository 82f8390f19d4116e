"""E040 speech-overlap: one robot cannot speak two lines at once.

With measured clips (after a build, or from the cache) an overlap is an error. When
lint has to estimate durations it is a warning (W040), unless the overlap is
certain whatever the durations (`with` a line of the same robot, or overlapping
the same robot's previous line).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity
from scriptc.layout import PlacedLine

CODE = "E040"
SLUG = "speech-overlap"
TIMING = True  # needs the layout


def check(ctx: Context) -> Iterator[Diagnostic]:
    if ctx.layout is None:
        return
    by_robot: dict[str, list[PlacedLine]] = {}
    for pl in ctx.layout.lines:
        by_robot.setdefault(pl.line.robot, []).append(pl)
    for robot, lines in by_robot.items():
        lines.sort(key=lambda p: (p.start, p.end))
        for a, b in itertools.pairwise(lines):
            if b.start >= a.end:
                continue
            certain = b.start == a.start or (a.info.exact and b.info.exact)
            sev = Severity.ERROR if certain else Severity.WARNING
            code = CODE if certain else "W040"
            extra = "" if certain else " (estimated durations)"
            yield Diagnostic(
                b.line.span,
                sev,
                code,
                f"{robot} is still speaking {a.line.cue} when {b.line.cue} starts{extra}",
                f"the lines overlap by {a.end - b.start}ms; add a gap or give the line "
                "to another robot",
            )
