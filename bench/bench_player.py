"""Player benchmarks, printed side by side in one run, with one core kept busy.

    python bench/bench_player.py [--quick]

1. Dispatch lateness over 2,000 events: scriptc's scheduler (sleep, then a short spin),
   the same without the spin, chained `time.sleep`, and asyncio `call_at`.
2. Skew between three `scriptc play` processes started by one OSC go: every robot does
   a gesture at the same instants, and for each instant we take the spread of the three
   processes' wall-clock times.
3. Gap accuracy: consecutive lines from different robots, actual gap (event logs) vs
   the written gap, next to the old counter hand-off re-created over local sockets.
4. Servo streaming: ten servos on the byte-level simulator through dynamixel_sdk, at
   100 Hz. Reports rate, tick jitter, and bus use as a fraction of the 1 Mbps wire.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import multiprocessing as mp
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

import itertools

import counter_handoff

from scriptc.build import build
from scriptc.player import plan as planlib
from scriptc.player.clock import ShowClock, parse_instant
from scriptc.player.dynamixel_out import DynamixelOutput
from scriptc.player.eventlog import EventLog
from scriptc.player.scheduler import Event, Scheduler
from scriptc.player.streamer import Streamer


def busy() -> None:
    while True:
        pass


def pct(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, round(q * (len(s) - 1)))]


def stats(values: list[float]) -> str:
    return (
        f"median {statistics.median(values):6.3f}  p99 {pct(values, 0.99):6.3f}  "
        f"max {max(values):7.3f} ms"
    )


# -- 1. dispatch lateness -------------------------------------------------------------------


def lateness_scheduler(n: int, spacing_ms: float, spin_ns: int) -> list[float]:
    clock = ShowClock(time.time_ns() + 100_000_000)
    late: list[float] = []
    events = [Event(i * spacing_ms, i, "x", lambda: None) for i in range(n)]
    Scheduler(
        clock, spin_ns=spin_ns, on_dispatch=lambda ev, actual, _w: late.append(actual - ev.at_ms)
    ).run(events)
    return late


def lateness_chained_sleep(n: int, spacing_ms: float) -> list[float]:
    t0 = time.monotonic_ns() + 100_000_000
    time.sleep(0.1)
    late = []
    for i in range(n):
        late.append((time.monotonic_ns() - (t0 + round(i * spacing_ms * 1e6))) / 1e6)
        time.sleep(spacing_ms / 1000)
    return late


def lateness_asyncio(n: int, spacing_ms: float) -> list[float]:
    late: list[float] = []

    async def main() -> None:
        loop = asyncio.get_running_loop()
        t0 = loop.time() + 0.1
        done = loop.create_future()
        base = time.monotonic_ns() + 100_000_000

        def fire(i: int) -> None:
            late.append((time.monotonic_ns() - (base + round(i * spacing_ms * 1e6))) / 1e6)
            if i == n - 1:
                done.set_result(None)

        for i in range(n):
            loop.call_at(t0 + i * spacing_ms / 1000, fire, i)
        await done

    asyncio.run(main())
    return late


# -- 2 and 3: three player processes ----------------------------------------------------------


def skew_play(n_lines: int) -> str:
    robots = ("ann", "bob", "cat")
    out = ["title: skew", "defaults: {gap: 150ms, engine: fixed}", "robots:"]
    for i, r in enumerate(robots):
        out += [
            f"  {r}:",
            "    joints:",
            f"      arm: {{id: {i + 1}, min: -90deg, max: 90deg, home: 0deg, max_speed: 360deg/s}}",
        ]
    out += [
        "gestures:",
        "  nod:",
        "    keyframes:",
        "      - {at: 200ms, ease: in-out, arm: 20deg}",
        "    then: home",
        "scenes:",
        "  - scene: s",
        "    lines:",
    ]
    for i in range(n_lines):
        r = robots[i % 3]
        out.append(f"      - {r}: Line number {i} is short.")
        for other in robots:
            out.append(f"      - {{robot: {other}, gesture: nod, with: previous}}")
    return "\n".join(out) + "\n"


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def three_players(tmp: Path, n_lines: int) -> tuple[list[float], list[float], list[float]]:
    (tmp / "skew.yaml").write_text(skew_play(n_lines))
    build(tmp / "skew.yaml", tmp / "build", cache_dir=tmp / "cache")
    robots = ["ann", "bob", "cat"]
    ports = {r: free_port() for r in robots}
    procs = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "scriptc",
                "play",
                str(tmp / "build"),
                "--robot",
                r,
                "--osc",
                f"127.0.0.1:{ports[r]}",
                "--audio",
                "null",
                "--servos",
                "sim",
                "--log",
                str(tmp / f"{r}.jsonl"),
                "--out",
                str(tmp / "sim"),
            ],
            stderr=subprocess.DEVNULL,
        )
        for r in robots
    ]
    for r in robots:
        while not ((tmp / f"{r}.jsonl").exists() and "waiting" in (tmp / f"{r}.jsonl").read_text()):
            time.sleep(0.05)
    subprocess.run(
        [
            sys.executable,
            "-m",
            "scriptc",
            "go",
            "--in",
            "1s",
            *[a for r in robots for a in ("--to", f"127.0.0.1:{ports[r]}")],
        ],
        check=True,
        stderr=subprocess.DEVNULL,
    )
    for p in procs:
        p.wait()
    logs = {
        r: [json.loads(x) for x in (tmp / f"{r}.jsonl").read_text().splitlines()] for r in robots
    }
    start = parse_instant(next(x for x in logs["ann"] if x["event"] == "go")["start"])

    def wall_ms(x: dict) -> float:  # type: ignore[type-arg]
        return (x["wall_ns"] - start) / 1e6

    by_time: dict[float, list[float]] = {}
    offsets: list[float] = []
    audio: list[dict] = []  # type: ignore[type-arg]
    for r in robots:
        for x in logs[r]:
            if x["event"] == "motion":
                by_time.setdefault(x["scheduled_ms"], []).append(wall_ms(x))
            if x["event"] in ("motion", "audio"):
                offsets.append(abs(wall_ms(x) - x["scheduled_ms"]))
            if x["event"] == "audio":
                audio.append(x)
    skews = [max(v) - min(v) for v in by_time.values() if len(v) == 3]
    tl = planlib.load(tmp / "build")
    dur = {a.cue: a.duration for p in tl.robots.values() for a in p.audio}
    audio.sort(key=lambda x: x["scheduled_ms"])
    gap_errors = []
    for a, b in itertools.pairwise(audio):
        written = b["scheduled_ms"] - (a["scheduled_ms"] + dur[a["cue"]])
        actual = wall_ms(b) - (wall_ms(a) + dur[a["cue"]])
        gap_errors.append(abs(actual - written))
    return skews, offsets, gap_errors


# -- 4. servo streaming -------------------------------------------------------------------------


def servo_stream(tmp: Path, seconds: float) -> tuple[float, list[float], float]:
    sim = subprocess.Popen(
        [sys.executable, "-m", "scriptc.player.servo_sim", "--ids", "1-10"],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert sim.stdout is not None
    port = sim.stdout.readline().strip()
    try:
        einstein = Path(__file__).resolve().parents[1] / "plays" / "einstein.yaml"
        build(einstein, tmp / "ein", cache_dir=tmp / "cache")
        plan = planlib.robots(planlib.load(tmp / "ein"), ["einstein"])[0]
        out = DynamixelOutput("einstein", plan.joints, plan.bus or {}, port=port)
        streamer = Streamer(plan, out, EventLog(None), rate_hz=100)
        streamer.prepare(0)
        clock = ShowClock(time.time_ns() + 200_000_000)
        streamer.run(clock, 0, seconds * 1000)  # then glides home, which is not counted
        out.close()
        ticks = streamer.stats.ticks
        wire_bits = streamer.stats.bus_bytes * 10  # 8N1: ten bits on the wire per byte
        late = [n / 1e6 for n in streamer.stats.late_ns]
        return ticks / seconds, late, wire_bits / seconds / out.baud
    finally:
        sim.kill()


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    n = 500 if args.quick else 2000
    hog = mp.get_context("spawn").Process(target=busy, daemon=True)
    hog.start()
    try:
        print(f"1. dispatch lateness over {n} events, 3 ms apart, one core busy")
        for name, late in [
            ("scriptc scheduler (sleep + 1 ms spin)", lateness_scheduler(n, 3.0, 1_000_000)),
            ("scriptc scheduler, no spin", lateness_scheduler(n, 3.0, 0)),
            ("chained time.sleep", lateness_chained_sleep(n, 3.0)),
            ("asyncio call_at", lateness_asyncio(n, 3.0)),
        ]:
            print(f"   {name:<40} {stats(late)}   last event {late[-1]:8.3f} ms")
        with tempfile.TemporaryDirectory() as tmp:
            skews, offsets, gaps = three_players(Path(tmp), 12 if args.quick else 40)
            print("2. three player processes, one OSC go, same-instant gestures")
            print(
                f"   skew between processes (max-min)       {stats(skews)}  ({len(skews)} instants)"
            )
            print(f"   every event vs schedule (wall clock)    {stats(offsets)}")
            print("3. gap accuracy, consecutive lines of different robots")
            print(f"   scriptc timeline: |actual - written gap| {stats(gaps)}")
            lines = [(i % 3, 600) for i in range(9 if args.quick else 24)]
            dead = counter_handoff.run(lines)
            print(f"   old counter hand-off: dead air per line  {stats(dead)}  (written gap 0 ms)")
            rate, jitter, bus = servo_stream(Path(tmp), 5.0 if args.quick else 15.0)
            print("4. servo streaming, 10 servos, Protocol 2.0 simulator on a pty, 1 Mbps")
            print(f"   rate {rate:6.1f} Hz (target >= 100)   tick lateness {stats(jitter)}")
            print(f"   bus use {bus * 100:5.1f}% of 1 Mbps (sync write each tick, sync read 10 Hz)")
    finally:
        hog.kill()


if __name__ == "__main__":
    main()
