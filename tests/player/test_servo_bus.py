"""The real dynamixel_sdk drives the byte-level simulator through the player."""

from __future__ import annotations

import itertools
import math
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from scriptc.player import plan as planlib
from scriptc.player.dxl_tables import MODELS
from scriptc.player.dynamixel_out import DynamixelOutput
from scriptc.player.player import PlayOptions, Start, perform
from scriptc.player.servo_out import ServoFault

XM = MODELS["xm430"]
StartSim = Callable[..., Any]


def _options(show: Path, port: str, tmp: Path, **kw: object) -> PlayOptions:
    return PlayOptions(
        show,
        ["ann"],
        Start(in_ms=600),
        audio="none",
        servos="dynamixel",
        port=port,
        log_path=tmp / "events.jsonl",
        **kw,
    )  # type: ignore[arg-type]


def _home_ticks(show: Path) -> dict[int, int]:
    plan = planlib.robots(planlib.load(show), ["ann"])[0]
    return {j.id: XM.to_tick(j.home) for j in plan.joints.values()}


def test_open_switches_torque_on_and_reads_the_pose(show: Path, servo_sim: StartSim) -> None:
    sim = servo_sim("--ids", "1-3")
    plan = planlib.robots(planlib.load(show), ["ann"])[0]
    out = DynamixelOutput("ann", plan.joints, plan.bus or {}, port=sim.port)
    pose = out.open()
    assert pose == {"shoulder": 0.0, "elbow": 0.0, "wrist": 0.0}  # the simulator starts centred
    out.write(0, {"shoulder": math.radians(30), "elbow": 0.0, "wrist": 0.0})
    out.close()
    deadline = time.monotonic() + 2
    while not sim.goals() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert sim.last_goal()[1] == XM.to_tick(math.radians(30))


def test_missing_servo_is_named(show: Path, servo_sim: StartSim) -> None:
    sim = servo_sim("--ids", "1-2")
    plan = planlib.robots(planlib.load(show), ["ann"])[0]
    with pytest.raises(ServoFault, match=r"servos 3 \(wrist\) do not answer"):
        DynamixelOutput("ann", plan.joints, plan.bus or {}, port=sim.port).open()


def test_whole_show_streams_within_limits_and_ends_home(
    show: Path, servo_sim, tmp_path: Path
) -> None:
    sim = servo_sim("--ids", "1-3")
    result = perform(_options(show, sim.port, tmp_path))
    assert result.exit_code == 0, result.faults
    goals = sim.goals()
    plan = planlib.robots(planlib.load(show), ["ann"])[0]
    for j in plan.joints.values():
        ticks = [g["goal"] for g in goals if g["id"] == j.id]
        assert min(ticks) >= XM.to_tick(j.min) and max(ticks) <= XM.to_tick(j.max)
    # The lift reaches 45 degrees on the shoulder and everything ends at home.
    assert max(g["goal"] for g in goals if g["id"] == 1) == XM.to_tick(math.radians(45))
    assert sim.last_goal() == _home_ticks(show)
    # About 100 goal writes a second per servo, each carrying all three servos.
    per_servo = [g for g in goals if g["id"] == 1]
    span = per_servo[-1]["t"] - per_servo[0]["t"]
    assert len(per_servo) / span > 60
    events = [r["event"] for r in result.log.records]
    assert events[:2] == ["ready", "start"] and events[-2:] == ["home", "end"]
    assert [r["cue"] for r in result.log.records if r["event"] == "motion"] == ["one/1", "two/2"]


def test_stop_sends_servos_home(show: Path, servo_sim: StartSim, tmp_path: Path) -> None:
    sim = servo_sim("--ids", "1-3")
    stop = threading.Event()
    threading.Timer(1.0, stop.set).start()  # mid-lift: the show starts 0.6 s in
    result = perform(_options(show, sim.port, tmp_path), stop=stop)
    assert result.exit_code == 130
    assert sim.last_goal() == _home_ticks(show)
    assert [r["event"] for r in result.log.records][-2:] == ["home", "end"]


def test_overload_mid_show_stops_the_robot_and_sends_the_rest_home(
    show: Path,
    servo_sim,
    tmp_path: Path,
) -> None:
    sim = servo_sim("--ids", "1-3", "--fault", "overload:2@1.0s")
    result = perform(_options(show, sim.port, tmp_path))
    assert result.exit_code == 3
    assert result.faults == ["ann: servo 2 (elbow): overload"]
    fault = next(r for r in result.log.records if r["event"] == "fault")
    assert fault["servo"] == 2 and fault["actual_ms"] < 2500  # found within a health check or two
    last = sim.last_goal()
    home = _home_ticks(show)
    assert last[1] == home[1] and last[3] == home[3]


def test_a_servo_that_stops_answering_is_a_fault(
    show: Path, servo_sim: StartSim, tmp_path: Path
) -> None:
    sim = servo_sim("--ids", "1-3", "--fault", "silent:3@0.8s")
    result = perform(_options(show, sim.port, tmp_path))
    assert result.exit_code == 3
    assert result.faults == ["ann: servo 3 (wrist) stopped answering"]
    assert sim.last_goal()[1] == _home_ticks(show)[1]


def test_protocol_1_servos(show: Path, servo_sim: StartSim, tmp_path: Path) -> None:
    sim = servo_sim("--ids", "1-3", "--protocol", "1")
    plan = planlib.robots(planlib.load(show), ["ann"])[0]
    bus = {"port": sim.port, "baud": 1000000, "protocol": 1, "model": "ax12"}
    out = DynamixelOutput("ann", plan.joints, bus)
    assert out.open() == pytest.approx({"shoulder": 0.0, "elbow": 0.0, "wrist": 0.0}, abs=0.01)
    out.write(0, {"shoulder": math.radians(-20), "elbow": 0.0, "wrist": 0.0})
    out.check()
    out.close()
    time.sleep(0.1)
    assert sim.last_goal()[1] == MODELS["ax12"].to_tick(math.radians(-20))


def test_targets_past_the_limits_are_clamped_on_the_wire(
    show: Path, servo_sim, tmp_path: Path
) -> None:
    """The compiler refuses such targets; the player still clamps a tampered timeline."""
    import json
    import shutil

    bad = tmp_path / "bad"
    shutil.copytree(show, bad)
    data = json.loads((bad / "timeline.json").read_text())
    track = data["robots"]["ann"]["motion"][0]["tracks"]["shoulder"]
    track[1][1] = 3.0  # far past the 60 degree limit, and an instant jump
    (bad / "timeline.json").write_text(json.dumps(data))
    sim = servo_sim("--ids", "1-3")
    result = perform(_options(bad, sim.port, tmp_path))
    assert result.exit_code == 0
    shoulder = [g for g in sim.goals() if g["id"] == 1]
    assert max(g["goal"] for g in shoulder) == XM.to_tick(math.radians(60))
    # No write moves further than 240 deg/s allows in one 10 ms tick (plus 5% slack and rounding).
    step = max(abs(a["goal"] - b["goal"]) for a, b in itertools.pairwise(shoulder))
    assert step <= XM.to_tick(math.radians(240) * 0.0105) - XM.center + 1


def test_sigterm_sends_servos_home(show: Path, servo_sim: StartSim, tmp_path: Path) -> None:
    import signal
    import subprocess
    import sys

    sim = servo_sim("--ids", "1-3")
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "scriptc",
            "play",
            str(show),
            "--robot",
            "ann",
            "--audio",
            "none",
            "--servos",
            "dynamixel",
            "--port",
            sim.port,
            "--start-in",
            "1s",
            "--log",
            str(tmp_path / "ev.jsonl"),
        ],
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 30
    while (
        not (tmp_path / "ev.jsonl").exists() or '"start"' not in (tmp_path / "ev.jsonl").read_text()
    ):
        assert time.monotonic() < deadline and proc.poll() is None
        time.sleep(0.05)
    time.sleep(1.3)  # inside the first lift
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=30) == 130
    assert sim.last_goal() == _home_ticks(show)
    events = [line for line in (tmp_path / "ev.jsonl").read_text().splitlines()]
    assert '"home"' in events[-2] and '"stopped"' in events[-1]


def test_missing_serial_port_refuses_to_start(show: Path, tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from scriptc.cli import app

    result = CliRunner().invoke(
        app,
        [
            "play",
            str(show),
            "--robot",
            "ann",
            "--servos",
            "dynamixel",
            "--port",
            str(tmp_path / "ttyNOPE"),
            "--audio",
            "none",
            "--start-in",
            "2s",
        ],
    )
    assert result.exit_code == 1
    assert "ann: cannot open servo bus" in result.output and "ttyNOPE" in result.output
