"""Show control over OSC: a `go` message carries the start instant; `stop` ends the show.

    /scriptc/go  <start>  [<cue>]     start: ISO 8601 text, Unix ns (int64) or Unix s (float)
    /scriptc/stop

`scriptc go` sends it; QLab or any show controller can too (a Network cue sending
`/scriptc/go "2026-11-22T20:00:05.000Z"`).
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Any

from scriptc.player.clock import parse_instant

GO = "/scriptc/go"
STOP = "/scriptc/stop"


@dataclass(frozen=True, slots=True)
class Go:
    start_wall_ns: int
    cue: str | None = None


def parse_go(args: tuple[Any, ...]) -> Go:
    if not args:
        raise ValueError("/scriptc/go needs the start instant")
    first = args[0]
    if isinstance(first, bool):
        raise ValueError("bad start instant")
    if isinstance(first, int):
        start = first if first > 10**15 else first * 1_000_000_000
    elif isinstance(first, float):
        start = round(first * 1e6) * 1000  # a float of seconds holds microseconds at best
    else:
        start = parse_instant(str(first))
    cue = str(args[1]) if len(args) > 1 and args[1] else None
    return Go(start, cue)


class GoListener:
    """Waits for a go (or stop) message on a UDP port."""

    def __init__(self, host: str, port: int) -> None:
        from pythonosc.dispatcher import Dispatcher
        from pythonosc.osc_server import ThreadingOSCUDPServer

        self.go: Go | None = None
        self.error: str | None = None
        self.got = threading.Event()
        self.stopped = threading.Event()
        d = Dispatcher()
        d.map(GO, self._on_go)
        d.map(STOP, self._on_stop)
        self.server = ThreadingOSCUDPServer((host, port), d)
        self.port = self.server.server_address[1]
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def _on_stop(self, _address: str, *args: Any) -> None:
        self.stopped.set()
        self.got.set()

    def _on_go(self, _address: str, *args: Any) -> None:
        try:
            self.go = parse_go(args)
        except ValueError as exc:
            self.error = str(exc)
            return
        self.got.set()

    def wait(self, timeout: float | None = None) -> Go | None:
        self.got.wait(timeout)
        return self.go

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()


def send_go(targets: list[tuple[str, int]], start_wall_ns: int, cue: str | None = None) -> None:
    from pythonosc.osc_message_builder import OscMessageBuilder
    from pythonosc.udp_client import SimpleUDPClient

    builder = OscMessageBuilder(address=GO)
    builder.add_arg(start_wall_ns, OscMessageBuilder.ARG_TYPE_INT64)
    if cue:
        builder.add_arg(cue)
    message = builder.build()
    for host, port in targets:
        client = SimpleUDPClient(host, port, allow_broadcast=True)
        client.send(message)


def send_stop(targets: list[tuple[str, int]]) -> None:
    from pythonosc.udp_client import SimpleUDPClient

    for host, port in targets:
        SimpleUDPClient(host, port, allow_broadcast=True).send_message(STOP, [])
