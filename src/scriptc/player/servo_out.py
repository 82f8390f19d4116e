"""Servo outputs behind one interface, and the safety clamp every target passes through.

`ServoOutput` is what the streamer talks to: `open` (return the present pose), `write`
(goal positions in radians), `check` (raise `ServoFault` on a hardware error), `close`.
`SimOutput` records the commanded trajectory for a look without hardware;
`dynamixel_out.DynamixelOutput` drives real servos through `dynamixel_sdk`.
"""

from __future__ import annotations

import json
from abc import ABC, abstractmethod
from pathlib import Path

from scriptc.player.plan import JointSpec

DEFAULT_MAX_SPEED = 6.0  # rad/s for joints with no max_speed


class ServoFault(Exception):
    """A servo reported a hardware error or stopped answering."""

    def __init__(self, message: str, *, servo: int | None = None) -> None:
        super().__init__(message)
        self.servo = servo


def clamp(
    joints: dict[str, JointSpec], targets: dict[str, float], last: dict[str, float], dt: float
) -> dict[str, float]:
    """Limit every target to its joint's range and to `max_speed * dt` from the last command."""
    out: dict[str, float] = {}
    for name, target in targets.items():
        j = joints[name]
        value = min(j.max, max(j.min, target))
        if name in last:
            step = (j.max_speed or DEFAULT_MAX_SPEED) * dt
            value = min(last[name] + step, max(last[name] - step, value))
        out[name] = value
    return out


class ServoOutput(ABC):
    """One robot's servos."""

    robot: str
    joints: dict[str, JointSpec]

    @abstractmethod
    def open(self) -> dict[str, float]:
        """Connect, switch torque on, and return the present pose in radians."""

    @abstractmethod
    def write(self, t_ms: float, targets: dict[str, float]) -> None:
        """Command goal positions (already clamped)."""

    def check(self) -> None:  # noqa: B027 - optional: outputs with no health report skip it
        """Raise `ServoFault` if a servo reports an error or has gone silent."""

    def close(self) -> None:  # noqa: B027 - optional: nothing to release by default
        """Release the bus."""

    def bus_bytes(self) -> int:
        """Bytes moved over the wire so far, both directions (0 where there is no wire)."""
        return 0


class SimOutput(ServoOutput):
    """Records every commanded pose; writes it as JSON and a picture when closed."""

    def __init__(
        self,
        robot: str,
        joints: dict[str, JointSpec],
        out_dir: Path | None = None,
        lines: list[tuple[int, int, str]] | None = None,
    ) -> None:
        self.robot = robot
        self.joints = joints
        self.out_dir = out_dir
        self.lines = lines or []
        self.samples: list[tuple[float, dict[str, float]]] = []

    def open(self) -> dict[str, float]:
        return {j.name: j.home for j in self.joints.values()}

    def write(self, t_ms: float, targets: dict[str, float]) -> None:
        self.samples.append((t_ms, dict(targets)))

    def close(self) -> None:
        if self.out_dir is None or not self.samples:
            return
        self.out_dir.mkdir(parents=True, exist_ok=True)
        data = {
            "robot": self.robot,
            "joints": list(self.joints),
            "samples": [
                [round(t, 3), [round(p[j], 5) for j in self.joints]] for t, p in self.samples
            ],
        }
        (self.out_dir / f"trajectory-{self.robot}.json").write_text(json.dumps(data) + "\n")
        from scriptc.player.trajectory_plot import plot

        plot(
            self.out_dir / f"trajectory-{self.robot}.png",
            self.robot,
            self.joints,
            self.samples,
            self.lines,
        )
