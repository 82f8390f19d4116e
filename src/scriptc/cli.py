"""The command line: parse flags, call a stage, render its result, exit. No logic lives here."""

from __future__ import annotations

import os
import sys
from enum import Enum
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, NoReturn

import typer

if TYPE_CHECKING:
    from scriptc.diagnostics import Diagnostic

app = typer.Typer(
    pretty_exceptions_enable=False,
    add_completion=False,
    no_args_is_help=True,
    rich_markup_mode=None,
    help="Compile a robot screenplay into one timeline and perform it in sync.",
)


class Format(str, Enum):
    auto = "auto"
    human = "human"
    plain = "plain"
    json = "json"
    github = "github"


def _err(message: str, code: int = 2) -> NoReturn:
    typer.echo(f"scriptc: error: {message}", err=True)
    raise typer.Exit(code)


def _show(diags: list[Diagnostic], fmt: Format, lines: object, *, err: bool = False) -> None:
    from scriptc import render

    name = fmt.value
    if name == "auto":
        name = "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "human"
    stream = sys.stderr if err else sys.stdout
    if name == "human":
        color = stream.isatty() and "NO_COLOR" not in os.environ
        text = render.human(diags, lines, color=color)  # type: ignore[arg-type]
        if color:
            from rich.console import Console
            from rich.text import Text

            Console(file=stream, highlight=False).print(Text.from_ansi(text), end="")
            return
    else:
        text = render.get(name)(diags, lines)
    stream.write(text)


def _exists(path: Path) -> None:
    if not path.is_file():
        _err(f"cannot read {path}: no such file")


CacheOpt = Annotated[
    Path, typer.Option("--cache", envvar="SCRIPTC_CACHE", help="Audio cache directory.")
]
EngineOpt = Annotated[
    str | None, typer.Option("--engine", help="Voice engine (default: the play's).")
]


@app.command()
def lint(
    play: Annotated[Path, typer.Argument(help="The screenplay YAML file.")],
    fmt: Annotated[Format, typer.Option("--format", "-f", help="Output format.")] = Format.auto,
    strict: Annotated[bool, typer.Option("--strict", help="Warnings fail too.")] = False,
    engine: EngineOpt = None,
    cache: CacheOpt = Path("audio_cache"),
) -> None:
    """Check a screenplay and report every problem with file:line:col."""
    from scriptc.diagnostics import Severity
    from scriptc.lint import lint as run

    _exists(play)
    result = run(play, engine=engine, cache_dir=cache)
    diags = list(result.report)
    _show(diags, fmt, result.source.text_of if result.source else None)
    worst = result.report.worst()
    if worst is Severity.ERROR or (strict and worst is Severity.WARNING):
        raise typer.Exit(1)


@app.command()
def build(
    play: Annotated[Path, typer.Argument(help="The screenplay YAML file.")],
    out: Annotated[Path | None, typer.Option("--out", "-o", help="Build directory.")] = None,
    engine: EngineOpt = None,
    cache: CacheOpt = Path("audio_cache"),
    jobs: Annotated[int, typer.Option("--jobs", "-j", min=1, help="Parallel synthesis jobs.")] = 2,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress or summary.")] = False,
    fmt: Annotated[
        Format, typer.Option("--format", "-f", help="Diagnostics format.")
    ] = Format.auto,
) -> None:
    """Synthesise every line, measure it and write a deterministic timeline with its clips."""
    from scriptc.build import build as run
    from scriptc.diagnostics import ScriptcError
    from scriptc.progress import bar

    _exists(play)
    try:
        with bar("synthesising", enabled=not quiet) as progress:
            result = run(play, out, engine=engine, cache_dir=cache, jobs=jobs, progress=progress)
    except ScriptcError as exc:
        if exc.diagnostics:
            from scriptc import source
            from scriptc.diagnostics import Report

            src = source.load(play, Report())
            _show(exc.diagnostics, fmt, src.text_of if src else None, err=True)
            raise typer.Exit(exc.exit_code) from None
        _err(exc.text, exc.exit_code)
    if result.report and not quiet:
        _show(list(result.report), fmt, None, err=True)
    if not quiet:
        tl = result.timeline
        lines = sum(len(r.audio) for r in tl.robots.values())
        typer.echo(
            f"built {lines} lines ({result.synthesized} synthesised) for {len(tl.robots)} robots, "
            f"{tl.duration / 1000:.1f}s -> {result.path}",
            err=True,
        )


@app.command()
def show(
    timeline: Annotated[Path, typer.Argument(help="A built timeline.json (or its directory).")],
    robot: Annotated[str | None, typer.Option("--robot", help="Only this robot.")] = None,
) -> None:
    """Print a built timeline as a table of cues."""
    from scriptc.showtable import show_timeline
    from scriptc.timeline import TimelineError, loads

    path = timeline / "timeline.json" if timeline.is_dir() else timeline
    _exists(path)
    try:
        tl = loads(path.read_text(encoding="utf-8"))
    except TimelineError as exc:
        _err(str(exc))
    show_timeline(tl, robot)


@app.command()
def voices(
    engine: Annotated[str, typer.Option("--engine", help="Voice engine.")] = "espeak",
) -> None:
    """List the voices an engine offers."""
    from scriptc.voices import registry
    from scriptc.voices.base import VoiceError

    try:
        found = registry.get(engine).voices()
    except VoiceError as exc:
        _err(f"{exc}" + (f" ({exc.hint})" if exc.hint else ""))
    for v in found:
        note = f"  {v.note}" if v.note else ""
        typer.echo(f"{v.id:<24} {v.language:<12} {v.gender}{note}".rstrip())


def main() -> None:
    try:
        app()
    except KeyboardInterrupt:
        typer.echo("scriptc: interrupted", err=True)
        sys.exit(130)
    except Exception as exc:  # a bug: say so briefly; SCRIPTC_DEBUG=1 shows the traceback
        if os.environ.get("SCRIPTC_DEBUG"):
            raise
        typer.echo(f"scriptc: internal error: {exc!r} (set SCRIPTC_DEBUG=1 for details)", err=True)
        sys.exit(3)
