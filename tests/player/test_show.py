"""Whole shows: rendered audio has its onsets where the timeline says, a file output writes
what was played, three player processes started by one OSC go keep together."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
import wave
from array import array
from pathlib import Path

import pytest
from typer.testing import CliRunner

from scriptc.cli import app
from scriptc.player import plan as planlib
from scriptc.player.osc import GoListener, parse_go, send_go
from scriptc.player.player import PlayOptions, Start, perform

runner = CliRunner()


def onsets(
    samples: array, rate: int, *, silence_ms: int = 120, threshold: int = 400
) -> list[float]:
    """Times (ms) where sound starts after at least `silence_ms` of near-silence."""
    found: list[float] = []
    quiet = silence_ms * rate // 1000
    run = quiet
    for i, s in enumerate(samples):
        if abs(s) > threshold:
            if run >= quiet:
                found.append(i * 1000 / rate)
            run = 0
        else:
            run += 1
    return found


def read_channels(path: Path) -> tuple[list[array], int]:
    with wave.open(str(path)) as w:
        n, rate = w.getnchannels(), w.getframerate()
        data = array("h", w.readframes(w.getnframes()))
    return [data[c::n] for c in range(n)], rate


def test_rendered_mixdown_has_onsets_where_the_timeline_says(show: Path, tmp_path: Path) -> None:
    out = tmp_path / "show.wav"
    result = runner.invoke(app, ["render", str(show), "-o", str(out)])
    assert result.exit_code == 0, result.output
    channels, rate = read_channels(out)
    tl = planlib.load(show)
    assert len(channels) == len(tl.robots)
    for channel, name in zip(channels, sorted(tl.robots), strict=False):
        expected = [a.start for a in tl.robots[name].audio]
        found = onsets(channel, rate)
        assert len(found) == len(expected), (name, found, expected)
        for f, e in zip(found, expected, strict=False):
            assert abs(f - e) <= 1.0, (name, f, e)


def test_panned_mixdown_is_stereo(show: Path, tmp_path: Path) -> None:
    out = tmp_path / "pan.wav"
    assert runner.invoke(app, ["render", str(show), "-o", str(out), "--mode", "pan"]).exit_code == 0
    (left, _right), rate = read_channels(out)
    tl = planlib.load(show)
    starts = sorted(a.start for r in tl.robots.values() for a in r.audio)
    assert abs(onsets(left, rate)[0] - starts[0]) <= 1.0


def test_file_output_writes_what_was_played_where_it_was_played(show: Path, tmp_path: Path) -> None:
    wav = tmp_path / "played.wav"
    result = perform(
        PlayOptions(
            show, ["all"], Start(in_ms=300), audio=f"file:{wav}", servos="sim", out_dir=tmp_path
        )
    )
    assert result.exit_code == 0
    played = [r for r in result.log.records if r["event"] == "audio"]
    tl = planlib.load(show)
    assert sorted(r["cue"] for r in played) == sorted(
        a.cue for p in tl.robots.values() for a in p.audio
    )
    (mono,), rate = read_channels(wav)
    found = onsets(mono, rate)
    actual = sorted(r["actual_ms"] for r in played)
    assert len(found) == len(actual)
    for f, a in zip(found, actual, strict=False):
        assert abs(f - a) <= 1.0  # at the offset each clip was actually started
    for r in played:
        assert abs(r["late_ms"]) < 50  # and that is close to the schedule
    assert (tmp_path / "trajectory-ann.png").stat().st_size > 1000


def test_null_audio_device_runs_in_real_time(show: Path, tmp_path: Path) -> None:
    t0 = time.monotonic()
    result = perform(
        PlayOptions(show, ["bob"], Start(in_ms=200), audio="null", servos="none", from_cue="second")
    )
    elapsed = time.monotonic() - t0
    audio = [r for r in result.log.records if r["event"] == "audio"]
    assert [r["cue"] for r in audio] == ["second"]
    tl = planlib.load(show)
    second = next(a for a in tl.robots["bob"].audio if a.cue == "second")
    assert elapsed >= (second.duration + 200) / 1000  # the NULL device plays in real time
    assert abs(audio[0]["late_ms"]) < 50


def test_from_cue_and_unknown_cue(show: Path, tmp_path: Path) -> None:
    result = runner.invoke(
        app, ["play", str(show), "--robot", "all", "--dry-run", "--from", "second"]
    )
    assert (
        result.exit_code == 0
        and "Second scene" in result.stdout
        and "Hello there" not in result.stdout
    )
    bad = runner.invoke(app, ["play", str(show), "--robot", "all", "--dry-run", "--from", "secnd"])
    assert bad.exit_code == 1 and "did you mean 'second'" in bad.output
    who = runner.invoke(app, ["play", str(show), "--robot", "bobb", "--dry-run"])
    assert who.exit_code == 1 and "did you mean 'bob'" in who.output


def test_damaged_clip_is_refused(show: Path, tmp_path: Path) -> None:
    import shutil

    copy = tmp_path / "copy"
    shutil.copytree(show, copy)
    clip = next((copy / "clips").iterdir())
    data = bytearray(clip.read_bytes())
    data[len(data) // 2] ^= 0xFF
    clip.write_bytes(bytes(data))
    result = runner.invoke(
        app,
        [
            "play",
            str(copy),
            "--robot",
            "all",
            "--start-in",
            "1s",
            "--audio",
            "none",
            "--servos",
            "none",
        ],
    )
    assert result.exit_code == 1 and "damaged" in result.output


def test_missing_sound_card_is_a_clear_error(show: Path) -> None:
    result = runner.invoke(
        app,
        [
            "play",
            str(show),
            "--robot",
            "bob",
            "--start-in",
            "1s",
            "--audio",
            "device",
            "--servos",
            "none",
        ],
    )
    assert result.exit_code == 1
    assert "no audio output device" in result.output and "--audio null" in result.output


def test_go_message_forms() -> None:
    assert parse_go((1_795_377_600_250_000_000,)).start_wall_ns == 1_795_377_600_250_000_000
    assert parse_go((1_795_377_600.25,)).start_wall_ns == 1_795_377_600_250_000_000
    assert parse_go(("2026-11-22T20:00:00.250Z", "second")).cue == "second"
    with pytest.raises(ValueError):
        parse_go(())


def test_go_reaches_a_listener() -> None:
    listener = GoListener("127.0.0.1", 0)
    try:
        send_go([("127.0.0.1", listener.port)], 1_795_377_600_250_000_000, "second")
        go = listener.wait(5)
        assert (
            go is not None and go.start_wall_ns == 1_795_377_600_250_000_000 and go.cue == "second"
        )
    finally:
        listener.close()


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_three_processes_started_by_one_go_stay_together(show: Path, tmp_path: Path) -> None:
    robots = ["ann", "bob", "cat"]
    ports = {r: _free_port() for r in robots}
    procs = {
        r: subprocess.Popen(
            [
                sys.executable,
                "-m",
                "scriptc",
                "play",
                str(show),
                "--robot",
                r,
                "--osc",
                f"127.0.0.1:{ports[r]}",
                "--audio",
                "null",
                "--servos",
                "sim",
                "--out",
                str(tmp_path),
                "--log",
                str(tmp_path / f"{r}.jsonl"),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for r in robots
    }
    deadline = time.monotonic() + 60
    for r in robots:  # wait until every player listens
        log = tmp_path / f"{r}.jsonl"
        while not (log.exists() and "waiting" in log.read_text()):
            assert procs[r].poll() is None, procs[r].stderr.read() if procs[r].stderr else ""
            assert time.monotonic() < deadline
            time.sleep(0.05)
    targets = [arg for r in robots for arg in ("--to", f"127.0.0.1:{ports[r]}")]
    go = runner.invoke(app, ["go", "--in", "1s", *targets])
    assert go.exit_code == 0
    for p in procs.values():
        assert p.wait(timeout=60) == 0, p.stderr.read() if p.stderr else ""
    tl = planlib.load(show)
    starts = set()
    for r in robots:
        records = [json.loads(x) for x in (tmp_path / f"{r}.jsonl").read_text().splitlines()]
        start = next(x for x in records if x["event"] == "go")["start"]
        starts.add(start)
        from scriptc.player.clock import parse_instant

        start_ns = parse_instant(start)
        timed = [x for x in records if x["event"] in ("audio", "motion")]
        expected = {("audio", a.cue) for a in tl.robots[r].audio} | {
            ("motion", m.cue) for m in tl.robots[r].motion
        }
        assert {(x["event"], x["cue"]) for x in timed} == expected
        for x in timed:
            # On the shared wall clock, each event happens where the schedule says.
            skew_ms = (x["wall_ns"] - start_ns) / 1e6 - x["scheduled_ms"]
            assert abs(skew_ms) < 50, (r, x)
    assert len(starts) == 1  # every player got the same instant


def test_every_run_leaves_an_event_log(show: Path, tmp_path: Path) -> None:
    result = runner.invoke(
        app,
        [
            "play",
            str(show),
            "--robot",
            "bob",
            "--audio",
            "none",
            "--servos",
            "none",
            "--start-in",
            "1s",
            "--from",
            "second",
            "--out",
            str(tmp_path),
        ],
    )
    assert result.exit_code == 0, result.output
    records = [json.loads(x) for x in (tmp_path / "events-bob.jsonl").read_text().splitlines()]
    assert [r["event"] for r in records] == ["start", "end"]  # no audio output, no servos
    assert records[-1]["status"] == "ok"
