"""Every broken screenplay gives a positioned diagnostic with the expected code and no traceback."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from scriptc.cli import app
from scriptc.lint import lint
from scriptc.source import MAX_BYTES

BAD = Path(__file__).parent / "bad"
CASES = sorted(BAD.glob("*.yaml"))
runner = CliRunner()


def _expected(path: Path) -> str:
    m = re.match(r"# expect: (\w+)", path.read_text(encoding="utf-8").splitlines()[0])
    assert m, f"{path.name} needs a `# expect: CODE` first line"
    return m.group(1)


def test_corpus_is_large_enough() -> None:
    assert len(CASES) >= 40


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.stem)
def test_broken_play_is_reported(path: Path) -> None:
    code = _expected(path)
    result = runner.invoke(app, ["lint", "--format", "json", str(path)])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    assert "Traceback" not in result.output
    diags = json.loads(result.stdout)
    found = [d for d in diags if d["code"] == code]
    assert found, f"expected {code}, got {[(d['code'], d['message']) for d in diags]}"
    for d in diags:
        assert d["line"] >= 1 and d["column"] >= 1 and d["file"].endswith(".yaml")
        assert d["message"]
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    d = found[0]
    if d["file"].endswith(path.name):
        assert d["line"] <= max(1, len(lines))
    expected_exit = 1 if any(x["severity"] == "error" for x in diags) else 0
    assert result.exit_code == expected_exit
    if expected_exit == 0:
        assert runner.invoke(app, ["lint", "--strict", str(path)]).exit_code == 1


def _generated(tmp_path: Path, name: str) -> Path:
    path = tmp_path / f"{name}.yaml"
    if name == "huge":
        path.write_bytes(b"title: x\n" + b"# padding\n" * (MAX_BYTES // 10 + 10))
    elif name == "binary":
        path.write_bytes(bytes(range(256)) * 16)
    elif name == "invalid-utf8":
        path.write_bytes(b"title: caf\xe9\nrobots: {}\n")
    elif name == "deep-nesting":
        path.write_text("title: " + "[" * 5000 + "]" * 5000 + "\n")
    elif name == "deep-mapping":
        path.write_text("".join("  " * i + f"k{i}:\n" for i in range(200)) + "  " * 200 + "x: 1\n")
    elif name == "empty":
        path.write_text("")
    elif name == "only-comments":
        path.write_text("# nothing here\n# at all\n")
    elif name == "many-documents":
        path.write_text("title: a\n---\ntitle: b\n")
    return path


@pytest.mark.parametrize(
    ("name", "code"),
    [
        ("huge", "E004"),
        ("binary", "E003"),
        ("invalid-utf8", "E003"),
        ("deep-nesting", "E005"),
        ("deep-mapping", "E005"),
        ("empty", "E013"),
        ("only-comments", "E013"),
        ("many-documents", "E001"),
    ],
)
def test_generated_junk_is_reported(tmp_path: Path, name: str, code: str) -> None:
    path = _generated(tmp_path, name)
    report = lint(path).report
    codes = [d.code for d in report]
    assert code in codes, codes
    result = runner.invoke(app, ["lint", "--format", "plain", str(path)])
    assert result.exit_code == 1
    assert re.search(rf"{re.escape(path.name)}:\d+:\d+: error {code} ", result.stdout)


def test_missing_file_is_a_usage_error(tmp_path: Path) -> None:
    result = runner.invoke(app, ["lint", str(tmp_path / "nope.yaml")])
    assert result.exit_code == 2
    assert "cannot read" in result.output


def test_example_play_is_clean() -> None:
    result = runner.invoke(
        app, ["lint", "--strict", str(Path(__file__).parents[1] / "plays/einstein.yaml")]
    )
    assert result.exit_code == 0, result.output
    assert result.stdout == ""
