"""A picture of a simulated performance: each joint's position over time, lines underneath."""

from __future__ import annotations

import math
from pathlib import Path

from scriptc.player.plan import JointSpec


def plot(
    path: Path,
    robot: str,
    joints: dict[str, JointSpec],
    samples: list[tuple[float, dict[str, float]]],
    lines: list[tuple[int, int, str]],
) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, lane) = plt.subplots(
        2, 1, figsize=(12, 6), sharex=True, gridspec_kw={"height_ratios": [4, 1]}
    )
    times = [t / 1000 for t, _ in samples]
    for name in joints:
        ax.plot(times, [math.degrees(p[name]) for _, p in samples], label=name, linewidth=1.2)
    ax.set_ylabel("commanded position (deg)")
    ax.set_title(f"{robot}: commanded servo trajectory")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=7, ncol=2)
    for start, duration, text in lines:
        lane.barh(0, duration / 1000, left=start / 1000, height=0.6, color="tab:blue", alpha=0.5)
        lane.text(start / 1000, 0, " " + text[:40], va="center", fontsize=6, clip_on=True)
    lane.set_yticks([])
    lane.set_xlabel("show time (s)")
    lane.set_ylabel("lines")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
