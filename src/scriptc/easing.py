"""Easing curves shared by the compiler's speed checks and the player's interpolation."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence


def _linear(t: float) -> float:
    return t


def _in(t: float) -> float:
    return t * t


def _out(t: float) -> float:
    return 1.0 - (1.0 - t) * (1.0 - t)


def _in_out(t: float) -> float:
    return t * t * (3.0 - 2.0 * t)


def _step(t: float) -> float:
    return 1.0 if t >= 1.0 else 0.0


CURVES: dict[str, Callable[[float], float]] = {
    "linear": _linear,
    "in": _in,
    "out": _out,
    "in-out": _in_out,
    "step": _step,
}

# The steepest slope of each curve relative to a straight line: a segment eased
# `in-out` peaks at 1.5x its average speed, so the speed check scales by this.
PEAK_SLOPE: dict[str, float] = {"linear": 1.0, "in": 2.0, "out": 2.0, "in-out": 1.5, "step": 1.0}


def position_at(track: Sequence[tuple[int, float, str]], t_ms: float) -> float:
    """Interpolate a track of (time ms, radians, ease into this point) at time `t_ms`."""
    if t_ms <= track[0][0]:
        return track[0][1]
    for (t0, p0, _), (t1, p1, ease) in itertools.pairwise(track):
        if t_ms < t1:
            frac = (t_ms - t0) / (t1 - t0) if t1 > t0 else 1.0
            return p0 + (p1 - p0) * CURVES[ease](frac)
    return track[-1][1]
