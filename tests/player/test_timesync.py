"""The pre-show clock check against a real SNTP exchange on loopback."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from scriptc.cli import app
from scriptc.player import timesync

runner = CliRunner()


@pytest.fixture
def time_server() -> Iterator[callable]:
    stops: list[threading.Event] = []

    def start(offset_ms: float) -> int:
        stop = threading.Event()
        stops.append(stop)
        ready: list[int] = []
        got = threading.Event()
        thread = threading.Thread(
            target=timesync.serve,
            args=(0,),
            daemon=True,
            kwargs={
                "host": "127.0.0.1",
                "stop": stop,
                "wall": lambda: time.time_ns() + int(offset_ms * 1e6),
                "ready": lambda port: (ready.append(port), got.set()),
            },
        )
        thread.start()
        got.wait(5)
        return ready[0]

    yield start
    for s in stops:
        s.set()


def test_offset_of_a_peer_ahead_by_40ms(time_server) -> None:  # type: ignore[no-untyped-def]
    port = time_server(40.0)
    m = timesync.offset(f"127.0.0.1:{port}")
    assert 35 < m.offset_ms < 45
    assert 0 <= m.delay_ms < 20


def test_in_sync_peer(time_server) -> None:  # type: ignore[no-untyped-def]
    m = timesync.offset(f"127.0.0.1:{time_server(0.0)}")
    assert abs(m.offset_ms) < 5


def test_no_answer_is_an_error() -> None:
    with pytest.raises(timesync.TimeSyncError, match="no answer"):
        timesync.offset("127.0.0.1:9", samples=1, timeout=0.2)


def test_player_refuses_to_start_past_the_bound(time_server, show: Path) -> None:  # type: ignore[no-untyped-def]
    port = time_server(40.0)
    args = [
        "play",
        str(show),
        "--robot",
        "bob",
        "--start-in",
        "1s",
        "--audio",
        "none",
        "--servos",
        "none",
        "--ntp",
        f"127.0.0.1:{port}",
    ]
    refused = runner.invoke(app, [*args, "--max-offset", "10ms"])
    assert refused.exit_code == 1 and "ms off 127.0.0.1" in refused.output
    allowed = runner.invoke(app, [*args, "--max-offset", "100ms", "--from", "second"])
    assert allowed.exit_code == 0, allowed.output
