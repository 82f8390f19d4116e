"""Fixtures for the player: a byte-level servo simulator on a pseudo-terminal, and timelines."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from scriptc.build import build

ROOT = Path(__file__).resolve().parents[2]


class SimServos:
    """A running `servo_sim` process; `goals()` reads every goal write it received."""

    def __init__(self, tmp: Path, *args: str) -> None:
        self.record = tmp / f"goals-{id(self)}.jsonl"
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "scriptc.player.servo_sim", "--record", str(self.record), *args],
            stdout=subprocess.PIPE,
            text=True,
        )
        assert self.proc.stdout is not None
        self.port = self.proc.stdout.readline().strip()
        assert self.port.startswith("/dev/"), self.port

    def goals(self) -> list[dict[str, Any]]:
        if not self.record.exists():
            return []
        return [json.loads(x) for x in self.record.read_text().splitlines() if x.strip()]

    def settle(self, quiet: float = 0.3, timeout: float = 5.0) -> None:
        """Wait until the simulator has handled every packet still in the pty."""
        import time

        deadline = time.monotonic() + timeout
        size, since = -1, time.monotonic()
        while time.monotonic() < deadline:
            now_size = self.record.stat().st_size if self.record.exists() else 0
            if now_size != size:
                size, since = now_size, time.monotonic()
            elif time.monotonic() - since >= quiet:
                return
            time.sleep(0.02)

    def last_goal(self) -> dict[int, int]:
        self.settle()
        last: dict[int, int] = {}
        for g in self.goals():
            last[g["id"]] = g["goal"]
        return last

    def stop(self) -> None:
        self.proc.kill()
        self.proc.wait()


@pytest.fixture
def servo_sim(tmp_path: Path) -> Iterator[Callable[..., SimServos]]:
    started: list[SimServos] = []

    def start(*args: str) -> SimServos:
        sim = SimServos(tmp_path, *args)
        started.append(sim)
        return sim

    yield start
    for sim in started:
        sim.stop()


PLAY = """
title: player test
defaults: {gap: 200ms}
robots:
  ann:
    voice: {fixed: a}
    bus: {port: /dev/null, baud: 1000000, protocol: 2}
    joints:
      shoulder: {id: 1, min: -60deg, max: 60deg, home: -20deg, max_speed: 240deg/s}
      elbow: {id: 2, min: -60deg, max: 60deg, home: 0deg, max_speed: 240deg/s}
      wrist: {id: 3, min: -60deg, max: 60deg, home: 10deg, max_speed: 240deg/s}
  bob:
    voice: {fixed: b}
  cat:
    voice: {fixed: c}
gestures:
  lift:
    keyframes:
      - {at: 400ms, ease: in-out, shoulder: 45deg, elbow: 20deg, wrist: -10deg}
      - {at: 900ms, shoulder: 45deg}
    then: home
scenes:
  - scene: one
    lines:
      - ann: Hello there.
        gesture: lift
      - bob: Good day.
      - cat: Welcome all.
  - scene: two
    gap: 300ms
    lines:
      - bob: Second scene.
        cue: second
      - ann: Last words here.
        gesture: lift
"""


@pytest.fixture(scope="session")
def show(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A small show built with the fixed test voice: 300 ms tone bursts per word."""
    tmp = tmp_path_factory.mktemp("show")
    (tmp / "play.yaml").write_text(PLAY)
    build(tmp / "play.yaml", tmp / "build", engine="fixed", cache_dir=tmp / "cache")
    return tmp / "build"
