"""Generate a large, valid screenplay for the benchmarks: N lines over three robots."""

from __future__ import annotations

import random
from pathlib import Path

WORDS = [
    "time",
    "space",
    "gravity",
    "apple",
    "light",
    "relative",
    "force",
    "motion",
    "energy",
    "mass",
    "orbit",
    "planet",
    "curve",
    "speed",
    "wave",
    "particle",
    "field",
    "theory",
    "moment",
    "inertia",
    "clock",
    "train",
    "falls",
]


def generate(n_lines: int, folder: Path, *, engine: str = "espeak", seed: int = 7) -> Path:
    """Write `play-N.yaml` into `folder` (with the example cast copied beside it)."""
    rng = random.Random(seed)
    cast = Path(__file__).resolve().parents[1] / "plays" / "cast"
    (folder / "cast").mkdir(parents=True, exist_ok=True)
    for f in cast.glob("*.yaml"):
        (folder / "cast" / f.name).write_text(f.read_text())
    robots = ("einstein", "dim", "newton")
    voices = {"einstein": "de", "dim": "en-us+m3", "newton": "en-gb"}
    out = [
        f"title: generated {n_lines}",
        "include: [cast/robots.yaml, cast/gestures.yaml]",
        f"defaults: {{gap: 200ms, engine: {engine}}}",
        "robots:",
        *(f"  {r}: {{voice: {{espeak: {voices[r]}, polly: Matthew}}}}" for r in robots),
        "scenes:",
    ]
    per_scene = 50
    for i in range(n_lines):
        if i % per_scene == 0:
            out += [f"  - scene: s{i // per_scene}", "    lines:"]
        robot = robots[i % 3]
        words = [rng.choice(WORDS) for _ in range(rng.randint(4, 12))]
        text = f"Line {i}, " + " ".join(words).capitalize() + "."
        out.append(f"      - {robot}: {text}")
        if i % per_scene and i % 7 == 3:
            out.append("        overlap: 150ms")
        if i % 10 == 5:
            out.append("        gestures:")
            out.append(f"          - {{gesture: nod, at: word {rng.randint(2, 4)}}}")
    path = folder / f"play-{n_lines}.yaml"
    path.write_text("\n".join(out) + "\n")
    return path
