from __future__ import annotations

import math

import pytest

from scriptc import units


@pytest.mark.parametrize(
    ("text", "ms"),
    [
        ("250ms", 250),
        ("1.5s", 1500),
        ("2min", 120000),
        (" 3 s ", 3000),
        (".5s", 500),
        (0, 0),
        ("0", 0),
    ],
)
def test_durations(text: object, ms: int) -> None:
    assert units.duration_ms(text) == ms


@pytest.mark.parametrize(
    "bad", ["250", 250, "fast", "1.5 parsecs", "-1s", True, None, [1], "1e400s"]
)
def test_bad_durations_say_what_is_expected(bad: object) -> None:
    with pytest.raises(units.UnitError) as exc:
        units.duration_ms(bad)
    assert str(exc.value)


def test_negative_duration_when_allowed() -> None:
    assert units.duration_ms("-200ms", allow_negative=True) == -200


def test_bare_number_hint_suggests_the_unit() -> None:
    with pytest.raises(units.UnitError, match="250ms"):
        units.duration_ms(250)


@pytest.mark.parametrize(
    ("text", "rad"),
    [
        ("45deg", math.pi / 4),
        ("0.5rad", 0.5),
        ("-30°", -math.pi / 6),
        ("180deg", math.pi),
    ],
)
def test_angles(text: str, rad: float) -> None:
    assert units.angle_rad(text) == pytest.approx(rad)


def test_angle_more_than_two_turns_is_rejected() -> None:
    with pytest.raises(units.UnitError, match="two turns"):
        units.angle_rad("1000deg")


@pytest.mark.parametrize(
    ("text", "rad_s"),
    [
        ("180deg/s", math.pi),
        ("3rad/s", 3.0),
        ("60rpm", 2 * math.pi),
    ],
)
def test_speeds(text: str, rad_s: float) -> None:
    assert units.speed_rad_s(text) == pytest.approx(rad_s)


@pytest.mark.parametrize("bad", ["3", "3deg", "-1rad/s", "0deg/s"])
def test_bad_speeds(bad: str) -> None:
    with pytest.raises(units.UnitError):
        units.speed_rad_s(bad)
