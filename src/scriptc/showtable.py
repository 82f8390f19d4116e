"""Print a timeline as a rich table: when each robot speaks and moves."""

from __future__ import annotations

from rich.console import Console
from rich.table import Table

from scriptc.timeline import Timeline


def _t(ms: int) -> str:
    return f"{ms // 60000}:{ms % 60000 / 1000:06.3f}"


def rows(tl: Timeline, robot: str | None = None) -> list[tuple[int, str, str, str, str, str]]:
    out = []
    for name, part in tl.robots.items():
        if robot and name != robot:
            continue
        for a in part.audio:
            out.append((a.start, _t(a.start), name, a.cue, f"{a.duration}ms", a.text))
        for m in part.motion:
            joints = ", ".join(m.tracks)
            out.append(
                (m.start, _t(m.start), name, m.cue, f"{m.duration}ms", f"~ {m.gesture} ({joints})")
            )
    return sorted(out)


def show_timeline(tl: Timeline, robot: str | None = None) -> None:
    table = Table(title=f"{tl.title} — {_t(tl.duration)} ({tl.engine})")
    for col in ("start", "robot", "cue", "length", "what"):
        table.add_column(col, overflow="fold")
    for _, *cols in rows(tl, robot):
        table.add_row(*cols)
    Console().print(table)
