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


def _hostport(text: str, default_host: str = "127.0.0.1") -> tuple[str, int]:
    host, _, port = text.rpartition(":")
    if not port.isdigit():
        _err(f"expected HOST:PORT or PORT, got {text!r}")
    return host or default_host, int(port)


def _ms(text: str, what: str) -> int:
    from scriptc import units

    try:
        return units.duration_ms(text)
    except units.UnitError as exc:
        _err(f"bad {what}: {exc}")


@app.command()
def play(
    build_dir: Annotated[Path, typer.Argument(help="A build directory (or its timeline.json).")],
    robot: Annotated[list[str], typer.Option("--robot", "-r", help="Robot to perform, or `all`.")],
    start_at: Annotated[
        str | None, typer.Option("--start-at", help="ISO 8601 start instant.")
    ] = None,
    start_in: Annotated[
        str | None, typer.Option("--start-in", help="Start after this long (5s).")
    ] = None,
    osc: Annotated[
        str | None, typer.Option("--osc", help="Wait for an OSC go on [HOST:]PORT.")
    ] = None,
    audio: Annotated[
        str, typer.Option("--audio", help="device, null, file:PATH or none.")
    ] = "device",
    servos: Annotated[str, typer.Option("--servos", help="dynamixel, sim or none.")] = "dynamixel",
    port: Annotated[
        str | None, typer.Option("--port", help="Serial port (one robot only).")
    ] = None,
    from_cue: Annotated[
        str | None, typer.Option("--from", help="Start at this cue or scene.")
    ] = None,
    dry_run: Annotated[
        bool, typer.Option("--dry-run", help="Print the schedule; touch nothing.")
    ] = False,
    log: Annotated[
        Path | None, typer.Option("--log", help="Event log (default BUILD/events-ROBOT.jsonl).")
    ] = None,
    rate: Annotated[float, typer.Option("--rate", help="Servo stream rate in Hz.")] = 100.0,
    ntp: Annotated[
        str | None, typer.Option("--ntp", help="Check the clock against HOST[:PORT].")
    ] = None,
    max_offset: Annotated[
        str, typer.Option("--max-offset", help="Refuse past this offset.")
    ] = "5ms",
    out: Annotated[Path | None, typer.Option("--out", help="Where sim trajectories go.")] = None,
    latency: Annotated[str, typer.Option("--audio-latency", help="Extra output latency.")] = "0ms",
) -> None:
    """Perform one robot's part (or all) against one shared clock."""
    import signal
    import threading

    from scriptc.player.plan import PlanError
    from scriptc.player.player import PlayerError, PlayOptions, Start, perform, schedule_rows

    try:
        if dry_run:
            from rich.console import Console
            from rich.table import Table

            table = Table(title=f"{build_dir} from {from_cue or 'the start'}")
            for col in ("time", "robot", "kind", "cue", "what"):
                table.add_column(col, overflow="fold")
            for t, name, kind, cue, what in schedule_rows(build_dir, robot, from_cue):
                table.add_row(f"{t / 1000:.3f}s", name, kind, cue, what)
            Console().print(table)
            return
        given = [x for x in (start_at, start_in, osc) if x]
        if len(given) != 1:
            _err("give exactly one of --start-at, --start-in or --osc")
        start = Start()
        if start_at:
            from scriptc.player.clock import parse_instant

            try:
                start.at_wall_ns = parse_instant(start_at)
            except ValueError as exc:
                _err(str(exc))
        elif start_in:
            start.in_ms = _ms(start_in, "--start-in")
        else:
            assert osc is not None
            start.osc = _hostport(osc, "0.0.0.0")
        base = out or (build_dir if build_dir.is_dir() else build_dir.parent)
        # Every run leaves an event log: --log, or events-<robots>.jsonl beside the build.
        log = log or base / f"events-{'-'.join(robot)}.jsonl"
        opts = PlayOptions(
            build_dir,
            robot,
            start,
            audio=audio,
            servos=servos,
            port=port,
            from_cue=from_cue,
            log_path=log,
            rate_hz=rate,
            ntp=ntp,
            max_offset_ms=_ms(max_offset, "--max-offset"),
            out_dir=base,
            audio_latency_ms=_ms(latency, "--audio-latency"),
        )
        stop = threading.Event()
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, lambda *_: stop.set())
        result = perform(opts, stop=stop)
    except PlanError as exc:
        _err(str(exc), 1)
    except PlayerError as exc:
        _err(str(exc), exc.exit_code)
    for fault in result.faults:
        typer.echo(f"scriptc: fault: {fault}; servos sent home", err=True)
    raise typer.Exit(result.exit_code)


@app.command()
def go(
    to: Annotated[list[str], typer.Option("--to", help="Player HOST:PORT (repeat for each).")],
    start_in: Annotated[str, typer.Option("--in", help="Start this long from now.")] = "3s",
    at: Annotated[str | None, typer.Option("--at", help="ISO 8601 start instant instead.")] = None,
    cue: Annotated[str | None, typer.Option("--cue", help="Cue the players start from.")] = None,
) -> None:
    """Send an OSC go carrying the start instant to every player."""
    import time

    from scriptc.player.clock import format_instant, parse_instant
    from scriptc.player.osc import send_go

    if at:
        try:
            instant = parse_instant(at)
        except ValueError as exc:
            _err(str(exc))
    else:
        instant = time.time_ns() + _ms(start_in, "--in") * 1_000_000
    send_go([_hostport(t) for t in to], instant, cue)
    typer.echo(f"go: show starts at {format_instant(instant)}", err=True)


@app.command()
def render(
    build_dir: Annotated[Path, typer.Argument(help="A build directory (or its timeline.json).")],
    out: Annotated[Path, typer.Option("--out", "-o", help="WAV file to write.")],
    mode: Annotated[
        str, typer.Option("--mode", help="channels (one per robot) or pan.")
    ] = "channels",
) -> None:
    """Write the whole show's mixdown for a listen before the show."""
    from scriptc.player.mixdown import render as run
    from scriptc.player.plan import PlanError

    if mode not in ("channels", "pan"):
        _err("--mode is channels or pan")
    try:
        channels, rate, frames = run(build_dir, out, mode=mode)
    except PlanError as exc:
        _err(str(exc), 1)
    typer.echo(f"wrote {out}: {channels} channels, {rate} Hz, {frames / rate:.1f}s", err=True)


@app.command()
def timeserver(port: Annotated[int, typer.Option("--port", help="UDP port.")] = 12300) -> None:
    """Answer SNTP queries from this host's clock, as the peer players check against."""
    from scriptc.player.timesync import serve

    typer.echo(f"serving SNTP on udp/{port}", err=True)
    serve(port)


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
