"""Dynamixel control tables as data: register addresses and sizes per servo model.

Addresses are from the ROBOTIS e-Manual (X-series Protocol 2.0, AX-series Protocol 1.0).
The player and the test simulator both read this table; the register names are an Enum.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass


class Reg(enum.Enum):
    MODEL_NUMBER = "model_number"
    TORQUE_ENABLE = "torque_enable"
    GOAL_POSITION = "goal_position"
    PRESENT_POSITION = "present_position"
    HARDWARE_ERROR = "hardware_error"
    PROFILE_VELOCITY = "profile_velocity"


@dataclass(frozen=True, slots=True)
class Model:
    """One servo model: protocol, position resolution and its registers."""

    name: str
    protocol: int
    model_number: int
    ticks: int  # positions over `span_rad`
    span_rad: float
    regs: dict[Reg, tuple[int, int]]  # address, size in bytes
    max_speed: float  # rad/s at no load, used by the simulator

    @property
    def center(self) -> int:
        return self.ticks // 2

    def to_tick(self, rad: float) -> int:
        tick = round(self.center + rad * self.ticks / self.span_rad)
        return max(0, min(self.ticks - 1, tick))

    def to_rad(self, tick: int) -> float:
        return (tick - self.center) * self.span_rad / self.ticks


_X = {
    Reg.MODEL_NUMBER: (0, 2),
    Reg.TORQUE_ENABLE: (64, 1),
    Reg.HARDWARE_ERROR: (70, 1),
    Reg.PROFILE_VELOCITY: (112, 4),
    Reg.GOAL_POSITION: (116, 4),
    Reg.PRESENT_POSITION: (132, 4),
}
_AX = {
    Reg.MODEL_NUMBER: (0, 2),
    Reg.TORQUE_ENABLE: (24, 1),
    Reg.GOAL_POSITION: (30, 2),
    Reg.PROFILE_VELOCITY: (32, 2),
    Reg.PRESENT_POSITION: (36, 2),
}

MODELS: dict[str, Model] = {
    "xm430": Model("xm430", 2, 1020, 4096, 2 * math.pi, _X, 4.8),
    "xl430": Model("xl430", 2, 1060, 4096, 2 * math.pi, _X, 6.1),
    "mx28": Model("mx28", 2, 30, 4096, 2 * math.pi, _X, 5.9),
    "mx64": Model("mx64", 2, 311, 4096, 2 * math.pi, _X, 6.6),
    "xm540": Model("xm540", 2, 1120, 4096, 2 * math.pi, _X, 3.2),
    "ax12": Model("ax12", 1, 12, 1024, math.radians(300), _AX, 6.2),
    "mx28-p1": Model(
        "mx28-p1", 1, 29, 4096, 2 * math.pi, {**_AX, Reg.PRESENT_POSITION: (36, 2)}, 5.9
    ),
}

# Hardware Error Status bits (Protocol 2.0, address 70) and Protocol 1.0 status error bits.
HW_ERRORS_P2 = {
    0: "input voltage",
    2: "overheating",
    3: "motor encoder",
    4: "electrical shock",
    5: "overload",
}
STATUS_ERRORS_P1 = {
    0: "input voltage",
    1: "angle limit",
    2: "overheating",
    3: "range",
    4: "checksum",
    5: "overload",
    6: "instruction",
}


def describe(bits: int, table: dict[int, str]) -> str:
    names = [name for bit, name in table.items() if bits & (1 << bit)]
    return ", ".join(names) or f"error 0x{bits:02x}"


def get(name: str) -> Model:
    if name not in MODELS:
        raise KeyError(f"unknown servo model {name!r}; known: {', '.join(MODELS)}")
    return MODELS[name]
