"""A re-creation of the old ROS design, for comparison: a counter node hands out line numbers.

The counter publishes the current line number (UDP on loopback). Each robot polls for
it in a 10 Hz loop (a `rospy.Rate(10)`), and when the line is its own it opens a fresh
audio pipeline (a new miniaudio NULL device), plays the clip in real time, closes the
pipeline and publishes `/increment`. That is two message hops, polling and a fresh
audio pipeline per line: the dead air the timeline player removes.

Run it through `bench_player.py`; it prints nothing by itself.
"""

from __future__ import annotations

import itertools
import json
import multiprocessing as mp
import socket
import time
from typing import Any

POLL_HZ = 10.0


def _counter(port: int, robot_ports: list[int], n_lines: int) -> None:
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", port))
    line = 0
    while line < n_lines:
        for rp in robot_ports:
            sock.sendto(str(line).encode(), ("127.0.0.1", rp))
        data, _ = sock.recvfrom(64)  # /increment
        line = int(data) + 1
    for rp in robot_ports:
        sock.sendto(b"-1", ("127.0.0.1", rp))


def _robot(
    index: int, port: int, counter_port: int, lines: list[tuple[int, int]], out: Any
) -> None:
    import miniaudio

    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", port))
    sock.setblocking(False)
    mine = {n: ms for n, (who, ms) in enumerate(lines) if who == index}
    current = None
    period = 1.0 / POLL_HZ
    next_poll = time.monotonic()
    played: list[tuple[int, float, float]] = []
    while True:
        try:
            while True:  # drain: keep the latest published number
                current = int(sock.recv(64))
        except BlockingIOError:
            pass
        if current == -1:
            break
        if current is not None and current in mine:
            ms = mine.pop(current)
            device = miniaudio.PlaybackDevice(
                output_format=miniaudio.SampleFormat.SIGNED16,
                nchannels=1,
                sample_rate=22050,
                buffersize_msec=20,
                backends=[miniaudio.Backend.NULL],
            )
            frames = 22050 * ms // 1000
            remaining = [frames]

            def clip(remaining: list[int] = remaining) -> Any:
                n = yield b""
                while True:
                    k = min(n, remaining[0])
                    remaining[0] -= k
                    n = yield b"\x00\x01" * k + b"\x00\x00" * (n - k)

            gen = clip()
            next(gen)
            started = time.time()
            device.start(gen)
            while remaining[0] > 0:
                time.sleep(0.001)
            ended = time.time()
            device.close()
            played.append((current, started, ended))
            sock.sendto(str(current).encode(), ("127.0.0.1", counter_port))
        next_poll += period
        time.sleep(max(0.0, next_poll - time.monotonic()))
    out.put(json.dumps(played))


def run(lines: list[tuple[int, int]], n_robots: int = 3, base_port: int = 47100) -> list[float]:
    """Play `lines` (robot index, duration ms); return the dead air between lines in ms."""
    ctx = mp.get_context("spawn")
    out = ctx.Queue()
    robot_ports = [base_port + 1 + i for i in range(n_robots)]
    robots = [
        ctx.Process(target=_robot, args=(i, robot_ports[i], base_port, lines, out))
        for i in range(n_robots)
    ]
    for p in robots:
        p.start()
    time.sleep(1.5)  # let the robots bind
    counter = ctx.Process(target=_counter, args=(base_port, robot_ports, len(lines)))
    counter.start()
    played = sorted(x for _ in robots for x in json.loads(out.get()))
    counter.join()
    for p in robots:
        p.join()
    return [(b[1] - a[2]) * 1000 for a, b in itertools.pairwise(played)]
