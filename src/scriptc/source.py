"""Read YAML files into a tree of positioned nodes, following `include:` lists.

ruamel.yaml composes the document (with its C parser when `ruamel.yaml.clib` is
installed); we turn the composed nodes into `Map`, `Seq` and `Scalar` values that
each carry a `Span`. Syntax errors, duplicate keys, recursive aliases, runaway
nesting, binary junk, oversized files, missing includes and include cycles all
become diagnostics; nothing here raises to the caller.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from scriptc.diagnostics import Report, Span

MAX_BYTES = 8 * 1024 * 1024
MAX_DEPTH = 64
MAX_INCLUDE_DEPTH = 16


@dataclass(slots=True)
class Scalar:
    span: Span
    value: str | int | float | bool | None


@dataclass(slots=True)
class Seq:
    span: Span
    items: list[Node] = field(default_factory=list)


@dataclass(slots=True)
class Map:
    span: Span
    entries: dict[str, tuple[Scalar, Node]] = field(default_factory=dict)

    def get(self, key: str) -> Node | None:
        entry = self.entries.get(key)
        return entry[1] if entry else None

    def key_span(self, key: str) -> Span:
        entry = self.entries.get(key)
        return entry[0].span if entry else self.span


Node = Scalar | Seq | Map


def kind_name(node: Node) -> str:
    """Name a node's type the way the diagnostics speak of it."""
    if isinstance(node, Map):
        return "a mapping"
    if isinstance(node, Seq):
        return "a list"
    v = node.value
    if v is None:
        return "nothing (null)"
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, (int, float)):
        return "a number"
    return "text"


@dataclass(slots=True)
class SourceFile:
    """One loaded YAML file: its display name, text lines and root node."""

    path: Path
    name: str
    lines: list[str]
    root: Node | None
    unreadable: bool = False


@dataclass(slots=True)
class Source:
    """The main file and everything it includes, in include order (main last)."""

    main: SourceFile
    files: list[SourceFile]

    def text_of(self, file: str) -> list[str]:
        for f in self.files:
            if f.name == file:
                return f.lines
        return []


def _display_name(path: Path, base: Path) -> str:
    try:
        return os.path.relpath(path, base)
    except ValueError:
        return str(path)


_PLAIN = re.compile(
    r"(?P<null>~|null|Null|NULL|)"
    r"|(?P<bool>true|True|TRUE|false|False|FALSE)"
    r"|(?P<int>[-+]?[0-9][0-9_]*|0o[0-7_]+|0x[0-9a-fA-F_]+)"
    r"|(?P<float>[-+]?(?:\.[0-9_]+|[0-9][0-9_]*(?:\.[0-9_]*)?)(?:[eE][-+]?[0-9]+)?"
    r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))"
)
_TAG = "tag:yaml.org,2002:"


def _fast_resolver() -> Any:
    """YAML 1.2 core-schema tags from one regular expression.

    ruamel's resolver walks a table of regular expressions for every scalar; with the C
    parser that was a third of the time spent reading a play.
    """
    from ruamel.yaml.nodes import ScalarNode, SequenceNode
    from ruamel.yaml.resolver import VersionedResolver

    class FastResolver(VersionedResolver):
        def resolve(self, kind: Any, value: Any, implicit: Any) -> str:
            if kind is ScalarNode:
                if implicit[0]:
                    m = _PLAIN.fullmatch(value)
                    if m is not None:
                        return _TAG + str(m.lastgroup)
                return _TAG + "str"
            return _TAG + ("seq" if kind is SequenceNode else "map")

    return FastResolver


def _yaml() -> Any:
    from ruamel.yaml import YAML

    try:
        import _ruamel_yaml  # noqa: F401
    except ImportError:  # pragma: no cover - depends on the platform
        return YAML(typ="safe", pure=True)
    y = YAML(typ="safe", pure=False)
    y.Resolver = _fast_resolver()
    return y


_BOOL_TRUE = {"true", "True", "TRUE"}


def _scalar_value(tag: str, text: str) -> str | int | float | bool | None:
    suffix = tag.rsplit(":", 1)[-1]
    if suffix == "int":
        cleaned = text.replace("_", "")
        try:
            return int(cleaned, 0)
        except ValueError:
            return text
    if suffix == "float":
        low = text.lower().replace("_", "")
        if low in (".inf", "+.inf"):
            return math.inf
        if low == "-.inf":
            return -math.inf
        if low == ".nan":
            return math.nan
        try:
            return float(low)
        except ValueError:
            return text
    if suffix == "bool":
        return text in _BOOL_TRUE or text.lower() in ("true", "yes", "on")
    if suffix == "null":
        return None
    return text


class _Converter:
    def __init__(self, name: str, report: Report) -> None:
        from ruamel.yaml.nodes import MappingNode, SequenceNode

        self.name = name
        self.report = report
        self.active: set[int] = set()
        self.mapping, self.sequence = MappingNode, SequenceNode

    def span(self, node: Any) -> Span:
        mark = node.start_mark
        return Span(self.name, mark.line + 1, mark.column + 1)

    def convert(self, node: Any, depth: int = 0) -> Node:
        span = self.span(node)
        if depth > MAX_DEPTH:
            self.report.error(
                span,
                "E005",
                f"nesting deeper than {MAX_DEPTH} levels",
                "a screenplay is at most a few levels deep; check the indentation",
            )
            return Scalar(span, None)
        if id(node) in self.active:
            self.report.error(span, "E006", "recursive alias", "an alias may not contain itself")
            return Scalar(span, None)
        if isinstance(node, self.sequence):
            self.active.add(id(node))
            seq = Seq(span, [self.convert(child, depth + 1) for child in node.value])
            self.active.discard(id(node))
            return seq
        if isinstance(node, self.mapping):
            self.active.add(id(node))
            result = Map(span)
            for key_node, value_node in node.value:
                key = self.convert(key_node, depth + 1)
                if not isinstance(key, Scalar) or isinstance(key.value, (bool, type(None))):
                    self.report.error(
                        key.span,
                        "E011",
                        "a key must be a name",
                        "write keys as plain words such as `robots:`",
                    )
                    continue
                text = str(key.value)
                if text == "<<":
                    self.report.error(
                        key.span,
                        "E011",
                        "merge keys (<<) are not supported",
                        "use an include file to share definitions",
                    )
                    continue
                if text in result.entries:
                    first = result.entries[text][0].span
                    self.report.error(
                        key.span,
                        "E014",
                        f"duplicate key {text!r}",
                        f"first defined at line {first.line}",
                    )
                    continue
                result.entries[text] = (Scalar(key.span, text), self.convert(value_node, depth + 1))
            self.active.discard(id(node))
            return result
        # `ctag.suffix` is the resolved tag; the `tag` property re-decodes it on every access.
        return Scalar(span, _scalar_value(str(node.ctag.suffix or ""), node.value))


def _syntax_error(exc: Exception, name: str, text: str, report: Report) -> None:
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    line = (mark.line + 1) if mark is not None else 1
    col = (mark.column + 1) if mark is not None else 1
    lines = text.splitlines()
    if lines and line > len(lines):  # an error at end of file: point at the last line's end
        line, col = len(lines), len(lines[-1]) + 1
    problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
    context = getattr(exc, "context", None)
    hint = context if context else "check the indentation and quoting around here"
    report.error(Span(name, line, col), "E001", f"YAML syntax error: {problem}", hint)


def _decode(data: bytes, name: str, report: Report) -> str | None:
    if b"\x00" in data[:8192]:
        report.error(
            Span(name, 1, 1),
            "E003",
            "file is binary, not YAML text",
            "a screenplay is a UTF-8 text file",
        )
        return None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        before = data[: exc.start]
        line = before.count(b"\n") + 1
        col = exc.start - (before.rfind(b"\n") + 1) + 1
        report.error(
            Span(name, line, col),
            "E003",
            f"invalid UTF-8 byte 0x{data[exc.start]:02x}",
            "save the file as UTF-8",
        )
        return None


def parse_text(text: str, name: str, report: Report) -> Node | None:
    """Compose one YAML document into positioned nodes, reporting any problem."""
    if len(text) > MAX_BYTES:
        report.error(
            Span(name, 1, 1),
            "E004",
            f"file is larger than {MAX_BYTES // (1024 * 1024)} MiB",
            "split the play with include files",
        )
        return None
    try:
        node = _yaml().compose(text)
    except RecursionError:
        report.error(
            Span(name, 1, 1),
            "E005",
            "nesting is too deep to read",
            "a screenplay is at most a few levels deep",
        )
        return None
    except Exception as exc:  # ruamel raises many error classes, all with marks
        _syntax_error(exc, name, text, report)
        return None
    if node is None:
        return None
    return _Converter(name, report).convert(node)


class _Loader:
    def __init__(self, base: Path, report: Report) -> None:
        self.base = base
        self.report = report
        self.loaded: dict[Path, SourceFile] = {}
        self.order: list[SourceFile] = []

    def load(self, path: Path, stack: tuple[Path, ...], where: Span | None) -> SourceFile | None:
        resolved = path.resolve()
        name = _display_name(resolved, self.base)
        if resolved in stack:
            chain = " -> ".join(_display_name(p, self.base) for p in (*stack, resolved))
            assert where is not None
            self.report.error(
                where, "E007", f"include cycle: {chain}", "remove one of these includes"
            )
            return None
        if resolved in self.loaded:
            return self.loaded[resolved]
        try:
            if resolved.stat().st_size > MAX_BYTES:
                self.report.error(
                    Span(name, 1, 1),
                    "E004",
                    f"file is larger than {MAX_BYTES // (1024 * 1024)} MiB",
                    "split the play with include files",
                )
                return None
            data = resolved.read_bytes()
        except OSError as exc:
            span = where or Span(name, 1, 1)
            reason = exc.strerror or str(exc)
            code, hint = ("E002", "paths are relative to the file that includes them")
            self.report.error(span, code, f"cannot read {name}: {reason}", hint)
            return None
        before = len(self.report)
        text = _decode(data, name, self.report)
        root = parse_text(text, name, self.report) if text is not None else None
        unreadable = root is None and len(self.report) > before
        source = SourceFile(resolved, name, (text or "").splitlines(), root, unreadable)
        self.loaded[resolved] = source
        if len(stack) >= MAX_INCLUDE_DEPTH:
            self.report.error(
                where or Span(name, 1, 1),
                "E007",
                f"includes nested deeper than {MAX_INCLUDE_DEPTH}",
                "flatten the include chain",
            )
        elif isinstance(root, Map):
            self._follow_includes(source, root, (*stack, resolved))
        self.order.append(source)
        return source

    def _follow_includes(self, source: SourceFile, root: Map, stack: tuple[Path, ...]) -> None:
        node = root.get("include")
        if node is None:
            return
        items = node.items if isinstance(node, Seq) else [node]
        for item in items:
            if not isinstance(item, Scalar) or not isinstance(item.value, str) or not item.value:
                self.report.error(
                    item.span,
                    "E011",
                    "an include is a file path",
                    "write `include: [robots.yaml, gestures.yaml]`",
                )
                continue
            self.load(source.path.parent / item.value, stack, item.span)


def load(path: Path, report: Report, *, base: Path | None = None) -> Source | None:
    """Load a screenplay and its includes; None if the main file cannot be read."""
    loader = _Loader(base or Path.cwd(), report)
    main = loader.load(path, (), None)
    if main is None:
        return None
    return Source(main, loader.order)
