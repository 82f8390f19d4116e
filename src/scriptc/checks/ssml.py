"""E061 ssml: a line that starts with `<speak` must be well-formed SSML.

The text is parsed as XML; the root must be `<speak>`. Tags Polly does not know
are warnings (W061), and a `<mark>` needs a `name`. The position points into the
line's text.
"""

from __future__ import annotations

from collections.abc import Iterator
from xml.etree import ElementTree

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity, Span, did_you_mean
from scriptc.model import Line

CODE = "E061"
SLUG = "ssml"
TIMING = False  # reads the play alone
TAGS = {
    "speak",
    "break",
    "emphasis",
    "lang",
    "mark",
    "p",
    "phoneme",
    "prosody",
    "s",
    "say-as",
    "sub",
    "w",
    "voice",
    "audio",
}
AMAZON = {"effect", "domain", "auto-breaths", "breath"}
AMAZON_NS = "{http://www.amazon.com/ssml}"


def _span(line: Line, position: tuple[int, int] | None) -> Span:
    base = line.text_span
    if position is None:
        return base
    row, col = position
    if row <= 1:
        return Span(base.file, base.line, base.col + col)
    return Span(base.file, base.line + row - 1, col + 1)


def check(ctx: Context) -> Iterator[Diagnostic]:
    for line in ctx.play.lines():
        if not line.ssml:
            continue
        text = line.text.replace("amazon:", "amazon_")
        try:
            root = ElementTree.fromstring(text)
        except ElementTree.ParseError as exc:
            msg = str(exc).split(":")[0]
            yield Diagnostic(
                _span(line, getattr(exc, "position", None)),
                Severity.ERROR,
                CODE,
                f"malformed SSML: {msg}",
                'every tag must be closed: <break time="1s"/>',
            )
            continue
        if root.tag != "speak":
            yield Diagnostic(
                line.text_span, Severity.ERROR, CODE, f"SSML root is <{root.tag}>, not <speak>"
            )
        for el in root.iter():
            tag = el.tag
            if tag.startswith("amazon_"):
                if tag[len("amazon_") :] not in AMAZON:
                    yield Diagnostic(
                        line.text_span,
                        Severity.WARNING,
                        "W061",
                        f"unknown SSML tag <{tag.replace('amazon_', 'amazon:')}>",
                    )
            elif tag not in TAGS:
                yield Diagnostic(
                    line.text_span,
                    Severity.WARNING,
                    "W061",
                    f"unknown SSML tag <{tag}>",
                    did_you_mean(tag, TAGS),
                )
            if tag == "mark" and not el.get("name"):
                yield Diagnostic(
                    line.text_span,
                    Severity.ERROR,
                    CODE,
                    "<mark> needs a name",
                    'write <mark name="here"/>',
                )
