"""Read anchor and reference expressions, and find the words and marks of a line.

Anchors say where in a line a gesture starts::

    start | end | word 3 | word "relativity" | mark wave_here | 1.2s    [+|- 200ms]

References say which earlier cue a line is placed against::

    previous | CUE_ID    [+|- 200ms]

Words are found in the written text (SSML tags skipped) with their character
offsets, so they can be matched to the offsets a voice engine reports.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from scriptc import units

_TAG = re.compile(r"<[^>]*>")
_WORD = re.compile(r"[\w'’-]*\w[\w'’-]*")  # at least one letter or digit
_MARK = re.compile(r"<mark\s+name\s*=\s*[\"']([^\"']*)[\"']\s*/?>")
_OFFSET = re.compile(r"^(.*?)\s*([+-])\s*(\d[\w.]*)\s*$")
_ANCHOR = re.compile(
    r"^(?:(?P<kw>start|end)|word\s+(?P<num>\d+)|word\s+[\"'](?P<word>[^\"']+)[\"']"
    r"|mark\s+(?P<mark>[\w.:-]+))$"
)


class AnchorError(ValueError):
    """An anchor or reference could not be read."""


@dataclass(frozen=True, slots=True)
class Word:
    """A written word and its character range in the line's text."""

    text: str
    start: int
    end: int


def words(text: str) -> list[Word]:
    """Split a line (plain or SSML) into words with character offsets."""
    if "<" not in text:
        return [Word(m.group(), m.start(), m.end()) for m in _WORD.finditer(text)]
    found: list[Word] = []
    pos = 0
    for tag in [*_TAG.finditer(text), None]:
        stop = tag.start() if tag else len(text)
        found += (Word(m.group(), m.start(), m.end()) for m in _WORD.finditer(text, pos, stop))
        if tag:
            pos = tag.end()
    return found


def marks(text: str) -> list[str]:
    """Names of the SSML `<mark name="..."/>` tags in a line."""
    return _MARK.findall(text)


def spoken_text(text: str) -> str:
    """The text with SSML tags removed (what Polly bills for)."""
    return _TAG.sub("", text)


def _split_offset(expr: str) -> tuple[str, int]:
    m = _OFFSET.match(expr)
    if m and m.group(1):
        try:
            offset = units.duration_ms(m.group(3))
        except units.UnitError as exc:
            raise AnchorError(str(exc)) from None
        return m.group(1), offset if m.group(2) == "+" else -offset
    return expr, 0


@dataclass(frozen=True, slots=True)
class ParsedAnchor:
    kind: str
    offset_ms: int
    index: int | None = None
    text: str | None = None


def parse_anchor(expr: object) -> ParsedAnchor:
    """Read `start`, `end`, `word N`, `word "text"`, `mark NAME` or a time, with an offset."""
    if not isinstance(expr, str):
        try:
            return ParsedAnchor("time", units.duration_ms(expr))
        except units.UnitError as exc:
            raise AnchorError(str(exc)) from None
    text = expr.strip()
    try:
        return ParsedAnchor("time", units.duration_ms(text))
    except units.UnitError:
        pass
    head, offset = _split_offset(text)
    m = _ANCHOR.match(head.strip())
    if not m:
        raise AnchorError(
            f"cannot read anchor {expr!r}: expected start, end, word N, "
            'word "text", mark NAME or a time such as 500ms'
        )
    if m.group("kw"):
        return ParsedAnchor(m.group("kw"), offset)
    if m.group("num"):
        index = int(m.group("num"))
        if index < 1:
            raise AnchorError("words are counted from 1")
        return ParsedAnchor("word", offset, index=index)
    if m.group("word"):
        return ParsedAnchor("word", offset, text=m.group("word"))
    return ParsedAnchor("mark", offset, text=m.group("mark"))


def parse_ref(expr: object) -> tuple[str, int]:
    """Read `previous` or a cue id, with an optional `+ 300ms` / `- 300ms` offset."""
    if not isinstance(expr, str) or not expr.strip():
        raise AnchorError("expected `previous` or a cue id, optionally `+ 300ms`")
    head, offset = _split_offset(expr.strip())
    name = head.strip()
    if not re.fullmatch(r"[\w.:/-]+", name):
        raise AnchorError(f"cannot read cue reference {expr!r}: expected `previous` or a cue id")
    return name, offset
