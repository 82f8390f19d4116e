"""Parse quantities the way people write them: `250ms`, `1.5s`, `45deg`, `0.5rad`, `180deg/s`.

Every parser returns the value in one internal unit (milliseconds as int, radians,
radians per second) or raises `UnitError` whose message says what was expected.
"""

from __future__ import annotations

import math
import re

_NUMBER = r"([+-]?(?:\d+(?:\.\d*)?|\.\d+))"
_QUANTITY = re.compile(_NUMBER + r"\s*([a-zA-Z°/]*)\Z")

_TIME_UNITS = {"ms": 1.0, "s": 1000.0, "sec": 1000.0, "min": 60000.0}
_ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0, "°": math.pi / 180.0}
_SPEED_UNITS = {
    "rad/s": 1.0,
    "deg/s": math.pi / 180.0,
    "°/s": math.pi / 180.0,
    "rpm": 2.0 * math.pi / 60.0,
}


class UnitError(ValueError):
    """A quantity could not be read; the message says what is expected."""


def _split(value: object, what: str, example: str) -> tuple[float, str]:
    if isinstance(value, bool):
        raise UnitError(f"expected {what} such as {example}, got {value!r}")
    if isinstance(value, (int, float)):
        if value == 0:
            return 0.0, ""
        raise UnitError(f"{what} needs a unit: write {value}{example.lstrip('0123456789.-')}")
    if not isinstance(value, str):
        raise UnitError(f"expected {what} such as {example}, got {type(value).__name__}")
    m = _QUANTITY.match(value.strip())
    if not m:
        raise UnitError(f"expected {what} such as {example}, got {value!r}")
    number, unit = float(m.group(1)), m.group(2).lower()
    if not math.isfinite(number):
        raise UnitError(f"{what} must be finite, got {value!r}")
    if unit == "" and number != 0:
        raise UnitError(f"{what} needs a unit: write {m.group(1)}{example.lstrip('0123456789.-')}")
    return number, unit


def duration_ms(value: object, *, allow_negative: bool = False) -> int:
    """Return a duration in whole milliseconds (`250ms`, `1.5s`, `2min`)."""
    number, unit = _split(value, "a duration", "250ms")
    if unit and unit not in _TIME_UNITS:
        raise UnitError(f"unknown time unit {unit!r}: use ms, s or min")
    ms = number * _TIME_UNITS.get(unit, 1.0)
    if ms < 0 and not allow_negative:
        raise UnitError(f"a duration cannot be negative, got {value!r}")
    if abs(ms) > 24 * 3600 * 1000:
        raise UnitError(f"duration {value!r} is longer than a day")
    return round(ms)


def angle_rad(value: object) -> float:
    """Return an angle in radians (`45deg`, `0.5rad`, `-30°`)."""
    number, unit = _split(value, "an angle", "45deg")
    if unit and unit not in _ANGLE_UNITS:
        raise UnitError(f"unknown angle unit {unit!r}: use deg or rad")
    rad = number * _ANGLE_UNITS.get(unit, 1.0)
    if abs(rad) > 4 * math.pi:
        raise UnitError(f"angle {value!r} is more than two turns")
    return rad


def speed_rad_s(value: object) -> float:
    """Return an angular speed in radians per second (`180deg/s`, `3rad/s`, `30rpm`)."""
    number, unit = _split(value, "a speed", "180deg/s")
    if unit not in _SPEED_UNITS:
        raise UnitError(f"unknown speed unit {unit!r}: use deg/s, rad/s or rpm")
    speed = number * _SPEED_UNITS[unit]
    if speed <= 0:
        raise UnitError(f"a speed must be positive, got {value!r}")
    return speed


def format_ms(ms: int) -> str:
    """Write milliseconds back the way a person would read them."""
    if ms % 1000 == 0 and ms != 0:
        return f"{ms // 1000}s"
    return f"{ms}ms"
