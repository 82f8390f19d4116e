"""The command line: formats, exit codes, and what lint must not import."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from typer.testing import CliRunner

from scriptc.cli import app

ROOT = Path(__file__).resolve().parents[1]
BAD = ROOT / "tests" / "bad" / "misspelt-line-key.yaml"
runner = CliRunner()


def test_human_format_shows_source_and_caret() -> None:
    out = runner.invoke(app, ["lint", "--format", "human", str(BAD)]).stdout
    lines = out.splitlines()
    assert lines[0].endswith(
        "misspelt-line-key.yaml:19:9: error E010 unknown key 'gesutre' in a line"
    )
    assert lines[1].strip() == "19 |         gesutre: wave"
    assert lines[2].index("^") == lines[1].index("g")
    assert "hint: did you mean 'gesture'" in lines[3]


def test_json_and_github_formats() -> None:
    data = json.loads(runner.invoke(app, ["lint", "-f", "json", str(BAD)]).stdout)
    assert data[0] | {"file": ""} == {
        "file": "",
        "line": 19,
        "column": 9,
        "severity": "error",
        "code": "E010",
        "message": "unknown key 'gesutre' in a line",
        "hint": "did you mean 'gesture' or 'gestures'?",
    }
    gh = runner.invoke(app, ["lint", "-f", "github", str(BAD)]).stdout
    assert gh.startswith("::error file=") and ",line=19,col=9,title=E010::unknown key" in gh


def test_auto_format_follows_github_actions(monkeypatch: object) -> None:
    result = runner.invoke(app, ["lint", str(BAD)], env={"GITHUB_ACTIONS": "true"})
    assert result.stdout.startswith("::error ")


def test_warnings_exit_zero_unless_strict(tmp_path: Path) -> None:
    play = tmp_path / "p.yaml"
    play.write_text(
        "robots:\n  a: {voice: {espeak: en-us}}\nscenes:\n  - lines: [{a: Hi.}]\n"
        "  - scene: empty\n    lines: []\n"
    )
    assert runner.invoke(app, ["lint", str(play)]).exit_code == 0
    assert runner.invoke(app, ["lint", "--strict", str(play)]).exit_code == 1


def test_usage_errors_exit_two() -> None:
    assert runner.invoke(app, ["lint"]).exit_code == 2
    assert runner.invoke(app, ["lint", "--format", "xml", str(BAD)]).exit_code == 2


def test_lint_imports_neither_boto3_nor_the_audio_stack() -> None:
    code = (
        "import sys\n"
        "from scriptc.cli import main\n"
        f"sys.argv = ['scriptc', 'lint', {str(ROOT / 'plays' / 'einstein.yaml')!r}]\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        "heavy = ('boto3', 'botocore', 'pydub', 'miniaudio', 'dynamixel_sdk')\n"
        "print([m for m in heavy if m in sys.modules])\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_voices_command() -> None:
    out = runner.invoke(app, ["voices", "--engine", "espeak"])
    assert out.exit_code == 0 and "en-us" in out.stdout.split()
    bad = runner.invoke(app, ["voices", "--engine", "espek"])
    assert bad.exit_code == 2 and "did you mean 'espeak'" in bad.output


def test_python_dash_m() -> None:
    out = subprocess.run(
        [sys.executable, "-m", "scriptc", "lint", str(BAD)], capture_output=True, text=True
    )
    assert out.returncode == 1 and "E010" in out.stdout
