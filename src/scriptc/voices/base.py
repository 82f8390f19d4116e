"""What every voice backend provides, and the values that pass between it and the build."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

from scriptc.model import PollySettings, Voice


class VoiceError(Exception):
    """Synthesis failed; the message says why and what to do. `cue` names the line."""

    def __init__(self, message: str, *, cue: str | None = None, hint: str | None = None) -> None:
        super().__init__(message)
        self.cue = cue
        self.hint = hint


@dataclass(frozen=True, slots=True)
class SynthJob:
    """One line to synthesise; `settings` holds everything else that changes the audio."""

    cue: str
    text: str
    ssml: bool
    voice: str
    lang: str | None
    settings: tuple[tuple[str, Any], ...] = ()

    def setting(self, name: str, default: Any = None) -> Any:
        return dict(self.settings).get(name, default)


@dataclass(frozen=True, slots=True)
class Synthesized:
    """A synthesised clip as 16-bit mono WAV bytes, with its word and mark timings."""

    wav: bytes
    words: tuple[tuple[int, int, int], ...]  # (char start, char end, ms)
    marks: tuple[tuple[str, int], ...] = ()
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class VoiceInfo:
    id: str
    language: str
    gender: str = ""
    note: str = ""


OnDone = Callable[[SynthJob, Synthesized], None]


class Backend(Protocol):
    """A text-to-speech engine. Backends register by name (see `registry`)."""

    name: str

    def identity(self) -> dict[str, str]:
        """Engine name and version: part of every cache key."""
        ...

    def job(
        self, cue: str, text: str, ssml: bool, voice: Voice | None, polly: PollySettings
    ) -> SynthJob:
        """The job for one line, with every setting that changes the audio filled in."""
        ...

    def synthesize(self, jobs: Sequence[SynthJob], *, workers: int, on_done: OnDone) -> None:
        """Synthesise `jobs`, calling `on_done` as each finishes; raise `VoiceError` on failure."""
        ...

    def voices(self) -> list[VoiceInfo]: ...
