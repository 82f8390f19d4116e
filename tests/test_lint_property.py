"""Lint never crashes: mutate valid plays at random and check it always answers with diagnostics."""

from __future__ import annotations

import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from scriptc.lint import lint

ROOT = Path(__file__).resolve().parents[1]
SEEDS = [ROOT / "plays" / "einstein.yaml", *sorted((ROOT / "tests" / "golden").glob("*/play.yaml"))]
TEXTS = [p.read_text(encoding="utf-8") for p in SEEDS]
TOKENS = [
    "- ",
    ": ",
    "{",
    "}",
    "[",
    "]",
    "'",
    '"',
    "&a ",
    "*a",
    "!!binary ",
    "\t",
    "\n",
    "    ",
    "~",
    "null",
    "250ms",
    "-1s",
    "1e999deg",
    "word 99",
    "mark x",
    "with: previous",
    "<speak>",
    "</x>",
    "gesture: wave",
    "robot: nobody",
    "\x00",
    "\ufeff",
    "include: [x.yaml]",
    "---",
    "%YAML 1.1\n",
]


@st.composite
def mutated(draw: st.DrawFn) -> tuple[str, str]:
    index = draw(st.integers(0, len(SEEDS) - 1))
    lines = TEXTS[index].splitlines(keepends=True)
    for _ in range(draw(st.integers(1, 6))):
        op = draw(st.sampled_from(["delete", "duplicate", "insert", "swap", "truncate", "indent"]))
        i = draw(st.integers(0, max(0, len(lines) - 1)))
        if not lines:
            break
        if op == "delete":
            del lines[i]
        elif op == "duplicate":
            lines.insert(i, lines[i])
        elif op == "insert":
            col = draw(st.integers(0, len(lines[i])))
            token = draw(st.sampled_from(TOKENS) | st.text(max_size=8))
            lines[i] = lines[i][:col] + token + lines[i][col:]
        elif op == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == "truncate":
            lines[i] = lines[i][: draw(st.integers(0, len(lines[i])))]
        else:
            lines[i] = "  " + lines[i]
    return str(SEEDS[index].parent), "".join(lines)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_lint_never_crashes(case: tuple[str, str]) -> None:
    folder, text = case
    # Written beside the seed so that its relative includes still resolve.
    with tempfile.NamedTemporaryFile(
        "w", suffix=".yaml", dir=folder, encoding="utf-8", errors="surrogatepass", delete=True
    ) as f:
        f.write(text)
        f.flush()
        result = lint(Path(f.name))
    for d in result.report:
        assert d.span.line >= 1 and d.span.col >= 1
        assert d.code[0] in "EW" and d.message


@settings(max_examples=100, deadline=None)
@given(st.binary(max_size=300))
def test_lint_survives_arbitrary_bytes(data: bytes) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "junk.yaml"
        path.write_bytes(data)
        result = lint(path)
    for d in result.report:
        assert d.span.line >= 1 and d.span.col >= 1
