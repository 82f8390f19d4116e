"""The screenplay checks, one per module, each with a `CODE`, a `SLUG`, `TIMING` (whether
it needs the layout) and a `check(ctx)` generator of diagnostics. The module docstring is
the rule's documentation."""

from __future__ import annotations

import importlib
from collections.abc import Iterator
from dataclasses import dataclass
from types import ModuleType

from scriptc.diagnostics import Diagnostic
from scriptc.layout import Layout
from scriptc.model import Play

MODULES = (
    "names",
    "voices",
    "joint_limits",
    "joint_speed",
    "speech_overlap",
    "joint_conflict",
    "polly_limits",
    "ssml",
    "empty_scene",
)


@dataclass(frozen=True, slots=True)
class Context:
    """What a check may look at: the play, its layout and the engines in use."""

    play: Play
    layout: Layout | None
    engine: str


def registry() -> dict[str, ModuleType]:
    """Check modules by slug."""
    mods = [importlib.import_module(f"scriptc.checks.{name}") for name in MODULES]
    return {m.SLUG: m for m in mods}


def get(slug: str) -> ModuleType:
    checks = registry()
    if slug not in checks:
        raise KeyError(f"unknown check {slug!r}; known: {', '.join(sorted(checks))}")
    return checks[slug]


def run_all(ctx: Context, *, timing: bool | None = None) -> Iterator[Diagnostic]:
    """Run every check, or only the timing checks (`timing=True`) or only the others."""
    for module in registry().values():
        if timing is None or timing == module.TIMING:
            yield from module.check(ctx)
