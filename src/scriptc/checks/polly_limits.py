"""E060 polly-limits: a line must fit in one Polly request.

Polly bills at most 3,000 characters of spoken text per request and accepts at
most 6,000 characters including SSML tags. The check runs for every play, since a
play written for the offline voice may later be built with Polly.
"""

from __future__ import annotations

from collections.abc import Iterator

from scriptc import anchors
from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity

CODE = "E060"
SLUG = "polly-limits"
TIMING = False  # reads the play alone
MAX_BILLED = 3000
MAX_TOTAL = 6000


def check(ctx: Context) -> Iterator[Diagnostic]:
    for line in ctx.play.lines():
        billed = len(anchors.spoken_text(line.text)) if line.ssml else len(line.text)
        if billed > MAX_BILLED:
            yield Diagnostic(
                line.text_span,
                Severity.ERROR,
                CODE,
                f"line has {billed} characters of text; Polly allows {MAX_BILLED}",
                "split it into several lines",
            )
        elif len(line.text) > MAX_TOTAL:
            yield Diagnostic(
                line.text_span,
                Severity.ERROR,
                CODE,
                f"line has {len(line.text)} characters with SSML; Polly allows {MAX_TOTAL}",
                "split it into several lines",
            )
