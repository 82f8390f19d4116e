"""The event log: one JSON line per event with its scheduled and actual time.

`scheduled_ms` and `actual_ms` are timeline times (actual from this host's monotonic
clock), `wall_ns` is this host's wall clock when it happened, so logs from several
hosts (or processes) can be compared on the shared wall-clock timebase.
"""

from __future__ import annotations

import json
import threading
import time
from pathlib import Path
from typing import IO, Any


class EventLog:
    def __init__(self, path: Path | None) -> None:
        self.lock = threading.Lock()
        self.file: IO[str] | None = open(path, "w", encoding="utf-8") if path else None  # noqa: SIM115
        self.records: list[dict[str, Any]] = []

    def write(
        self,
        event: str,
        *,
        robot: str | None = None,
        cue: str | None = None,
        scheduled_ms: float | None = None,
        actual_ms: float | None = None,
        wall_ns: int | None = None,
        **extra: Any,
    ) -> dict[str, Any]:
        rec: dict[str, Any] = {"event": event}
        if robot is not None:
            rec["robot"] = robot
        if cue is not None:
            rec["cue"] = cue
        if scheduled_ms is not None:
            rec["scheduled_ms"] = round(scheduled_ms, 3)
        if actual_ms is not None:
            rec["actual_ms"] = round(actual_ms, 3)
            if scheduled_ms is not None:
                rec["late_ms"] = round(actual_ms - scheduled_ms, 3)
        rec["wall_ns"] = time.time_ns() if wall_ns is None else wall_ns
        rec.update(extra)
        with self.lock:
            self.records.append(rec)
            if self.file:
                self.file.write(json.dumps(rec, sort_keys=True) + "\n")
                self.file.flush()
        return rec

    def close(self) -> None:
        with self.lock:
            if self.file:
                self.file.close()
                self.file = None


def read(path: Path) -> list[dict[str, Any]]:
    return [
        json.loads(line) for line in path.read_text(encoding="utf-8").splitlines() if line.strip()
    ]
