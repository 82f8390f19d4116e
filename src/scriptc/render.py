"""Render diagnostics: one place for every output format.

`human` shows the source line with a caret under the column (in colour on a
terminal), `plain` is `file:line:col: severity code message` for editors, `json`
a list of objects, `github` workflow annotation commands.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Sequence

from scriptc.diagnostics import Diagnostic, Severity

Lines = Callable[[str], Sequence[str]]


def plain(diags: Iterable[Diagnostic], source_lines: Lines | None = None) -> str:
    out = []
    for d in diags:
        hint = f" ({d.hint})" if d.hint else ""
        out.append(f"{d.span}: {d.severity.label} {d.code} {d.message}{hint}")
    return "\n".join(out) + ("\n" if out else "")


def human(
    diags: Iterable[Diagnostic], source_lines: Lines | None = None, *, color: bool = False
) -> str:
    styles = {
        Severity.ERROR: "\x1b[1;31m",
        Severity.WARNING: "\x1b[1;33m",
        Severity.INFO: "\x1b[1;34m",
    }
    bold, dim, reset = ("\x1b[1m", "\x1b[2m", "\x1b[0m") if color else ("", "", "")
    out = []
    for d in diags:
        sev = f"{styles[d.severity]}{d.severity.label}{reset}" if color else d.severity.label
        out.append(f"{bold}{d.span}{reset}: {sev} {d.code} {d.message}")
        lines = source_lines(d.span.file) if source_lines else ()
        if 0 < d.span.line <= len(lines):
            text = lines[d.span.line - 1].replace("\t", " ")
            if len(text) > 160:
                start = max(0, d.span.col - 60)
                text = text[start : start + 160]
                caret_col = d.span.col - start
            else:
                caret_col = d.span.col
            out.append(f"  {dim}{d.span.line:>4} |{reset} {text}")
            caret = f"{styles[d.severity] if color else ''}^{reset}"
            out.append(f"       {dim}|{reset} {' ' * (caret_col - 1)}{caret}")
        if d.hint:
            out.append(f"       = hint: {d.hint}")
    return "\n".join(out) + ("\n" if out else "")


def as_json(diags: Iterable[Diagnostic], source_lines: Lines | None = None) -> str:
    return (
        json.dumps(
            [
                {
                    "file": d.span.file,
                    "line": d.span.line,
                    "column": d.span.col,
                    "severity": d.severity.label,
                    "code": d.code,
                    "message": d.message,
                    "hint": d.hint,
                }
                for d in diags
            ],
            indent=2,
        )
        + "\n"
    )


def _escape(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def github(diags: Iterable[Diagnostic], source_lines: Lines | None = None) -> str:
    level = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}
    out = []
    for d in diags:
        hint = f" ({d.hint})" if d.hint else ""
        out.append(
            f"::{level[d.severity]} file={d.span.file},line={d.span.line},col={d.span.col},"
            f"title={d.code}::{_escape(d.message + hint)}"
        )
    return "\n".join(out) + ("\n" if out else "")


FORMATS: dict[str, Callable[..., str]] = {
    "human": human,
    "plain": plain,
    "json": as_json,
    "github": github,
}


def get(name: str) -> Callable[..., str]:
    if name not in FORMATS:
        raise KeyError(f"unknown format {name!r}; known: {', '.join(FORMATS)}")
    return FORMATS[name]
