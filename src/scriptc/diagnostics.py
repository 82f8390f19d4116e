"""Diagnostics: small immutable values that say what is wrong, where, and how to fix it.

A `Diagnostic` carries a 1-based line and column, a code, a severity, a message and an
optional hint. Every stage appends to a `Report`; nothing stops at the first problem.
"""

from __future__ import annotations

import difflib
import enum
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field


class Severity(enum.IntEnum):
    """How bad a problem is; the highest one decides the exit code."""

    INFO = 0
    WARNING = 1
    ERROR = 2

    @property
    def label(self) -> str:
        return self.name.lower()


@dataclass(frozen=True, slots=True, order=True)
class Span:
    """A position in a source file: 1-based line and column."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


@dataclass(frozen=True, slots=True, order=True)
class Diagnostic:
    """One problem found in a screenplay."""

    span: Span
    severity: Severity = field(compare=False)
    code: str
    message: str
    hint: str | None = field(default=None, compare=False)

    def __repr__(self) -> str:
        return f"{self.span}: {self.code} {self.message}"


class Report:
    """Collects diagnostics from every stage and answers whether any is an error."""

    def __init__(self) -> None:
        self._items: list[Diagnostic] = []
        self._seen: set[tuple[Span, str, str]] = set()

    def add(
        self,
        span: Span,
        severity: Severity,
        code: str,
        message: str,
        hint: str | None = None,
    ) -> None:
        key = (span, code, message)
        if key not in self._seen:
            self._seen.add(key)
            self._items.append(Diagnostic(span, severity, code, message, hint))

    def error(self, span: Span, code: str, message: str, hint: str | None = None) -> None:
        self.add(span, Severity.ERROR, code, message, hint)

    def warning(self, span: Span, code: str, message: str, hint: str | None = None) -> None:
        self.add(span, Severity.WARNING, code, message, hint)

    def extend(self, items: Iterable[Diagnostic]) -> None:
        for d in items:
            self.add(d.span, d.severity, d.code, d.message, d.hint)

    def __iter__(self) -> Iterator[Diagnostic]:
        return iter(sorted(self._items))

    def __len__(self) -> int:
        return len(self._items)

    @property
    def has_errors(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self._items)

    def worst(self) -> Severity | None:
        return max((d.severity for d in self._items), default=None)


class ScriptcError(Exception):
    """A failure that stops a command, reported as diagnostics and never as a traceback."""

    def __init__(self, diagnostics: Iterable[Diagnostic] | str, *, exit_code: int = 1) -> None:
        if isinstance(diagnostics, str):
            self.diagnostics: list[Diagnostic] = []
            self.text = diagnostics
        else:
            self.diagnostics = sorted(diagnostics)
            self.text = "; ".join(repr(d) for d in self.diagnostics)
        self.exit_code = exit_code
        super().__init__(self.text)


def did_you_mean(name: str, choices: Iterable[str]) -> str | None:
    """Return a `did you mean ...?` hint for a misspelt name, or None."""
    close = difflib.get_close_matches(name, list(choices), n=3, cutoff=0.6)
    if not close:
        lowered = {c.lower(): c for c in choices}
        if name.lower() in lowered:
            close = [lowered[name.lower()]]
    if not close:
        return None
    return "did you mean " + " or ".join(repr(c) for c in close) + "?"


def known(choices: Iterable[str], limit: int = 8) -> str:
    """Return a short `known: a, b, c` hint listing the valid names."""
    names = sorted(choices)
    more = f", … ({len(names) - limit} more)" if len(names) > limit else ""
    return "known: " + ", ".join(names[:limit]) + more if names else "none is defined"
