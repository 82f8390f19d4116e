"""E023 voices: every voice a robot names must exist in its engine.

eSpeak NG voices are checked against the data files in the embedded wheel
(`de`, `en-us`, `en-us+m3`); Polly voice ids and language codes against
botocore's bundled service model, so the check works offline. A robot with no
voice for the engine in use gets a warning and the engine's default voice.
"""

from __future__ import annotations

from collections.abc import Iterator

from scriptc.checks import Context
from scriptc.diagnostics import Diagnostic, Severity, did_you_mean
from scriptc.voices import catalog, registry

CODE = "E023"
SLUG = "voices"
TIMING = False  # reads the play alone


def check(ctx: Context) -> Iterator[Diagnostic]:
    engines = set(registry.BUILTIN)
    spoken = {line.robot for line in ctx.play.lines()}
    for robot in ctx.play.robots.values():
        for engine, voice in robot.voices.items():
            if engine not in engines and engine not in registry.names():
                yield Diagnostic(
                    voice.span,
                    Severity.ERROR,
                    CODE,
                    f"unknown voice engine {engine!r}",
                    did_you_mean(engine, registry.names()),
                )
                continue
            if engine == "espeak":
                problem = catalog.espeak_voice_ok(voice.id)
                if problem:
                    lang = voice.id.partition("+")[0]
                    yield Diagnostic(
                        voice.span,
                        Severity.ERROR,
                        CODE,
                        problem,
                        did_you_mean(lang, catalog.espeak_languages()),
                    )
            elif engine == "polly":
                known = catalog.polly_voices()
                if known and voice.id not in known:
                    yield Diagnostic(
                        voice.span,
                        Severity.ERROR,
                        CODE,
                        f"Polly has no voice {voice.id!r}",
                        did_you_mean(voice.id, known),
                    )
                langs = catalog.polly_languages()
                if voice.lang and langs and voice.lang not in langs:
                    yield Diagnostic(
                        voice.span,
                        Severity.ERROR,
                        CODE,
                        f"Polly has no language code {voice.lang!r}",
                        did_you_mean(voice.lang, langs),
                    )
        if robot.name in spoken and ctx.engine not in robot.voices and ctx.engine != "fixed":
            yield Diagnostic(
                robot.span,
                Severity.WARNING,
                "W023",
                f"{robot.name} has no {ctx.engine} voice; the engine's default is used",
                f"add `voice: {{{ctx.engine}: ...}}`",
            )
