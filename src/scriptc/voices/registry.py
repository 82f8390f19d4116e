"""Voice backends by name: the built-in ones and any installed through the
`scriptc.voices` entry point group (a class taking no arguments)."""

from __future__ import annotations

import importlib
from importlib.metadata import entry_points
from typing import Any

from scriptc.voices.base import Backend, VoiceError

BUILTIN: dict[str, str] = {
    "espeak": "scriptc.voices.espeak:EspeakBackend",
    "polly": "scriptc.voices.polly:PollyBackend",
    "fixed": "scriptc.voices.fixed:FixedBackend",
}
GROUP = "scriptc.voices"


def _plugins() -> dict[str, Any]:
    return {ep.name: ep for ep in entry_points(group=GROUP)}


def names() -> list[str]:
    """Every backend name that `get` accepts."""
    return sorted({*BUILTIN, *_plugins()})


def get(name: str, **options: Any) -> Backend:
    """Instantiate the backend called `name`, or fail with the names that exist."""
    if name in BUILTIN:
        module, _, attr = BUILTIN[name].partition(":")
        cls = getattr(importlib.import_module(module), attr)
    else:
        plugin = _plugins().get(name)
        if plugin is None:
            from scriptc.diagnostics import did_you_mean

            hint = did_you_mean(name, names()) or "known: " + ", ".join(names())
            raise VoiceError(f"unknown voice engine {name!r}", hint=hint)
        cls = plugin.load()
    backend: Backend = cls(**options)
    return backend
