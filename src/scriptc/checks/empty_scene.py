"""W070 empty-scene: a scene with no lines, pauses or cues is probably a mistake;
a play with no line at all cannot be built (E070)."""

from __future__ import annotations

from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity

CODE = "W070"
SLUG = "empty-scene"
TIMING = False  # reads the play alone


def check(ctx: Context) -> Iterator[Diagnostic]:
    for scene in ctx.play.scenes:
        if not scene.items:
            yield Diagnostic(
                scene.span,
                Severity.WARNING,
                CODE,
                f"scene {scene.id!r} is empty",
                "add lines or remove the scene",
            )
    if ctx.play.scenes and not ctx.play.lines():
        yield Diagnostic(
            ctx.play.span,
            Severity.ERROR,
            "E070",
            "the play has no spoken line",
            "add a line such as `- einstein: Good evening.`",
        )
