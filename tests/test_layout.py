"""The time model, with clips of known length so every start can be worked out by hand."""

from __future__ import annotations

from pathlib import Path

from scriptc import parse, source
from scriptc.diagnostics import Report
from scriptc.layout import ClipInfo, Layout, layout

ROBOTS = """
robots:
  a:
    joints:
      arm: {id: 1, min: -90deg, max: 90deg, home: 0deg}
  b:
    joints:
      arm: {id: 1, min: -90deg, max: 90deg, home: 0deg}
gestures:
  up:
    keyframes:
      - {at: 1s, arm: 30deg}
    then: hold
"""


def _layout(tmp_path: Path, scenes: str, clips: dict[str, int]) -> tuple[Layout, Report]:
    path = tmp_path / "p.yaml"
    path.write_text(ROBOTS + scenes)
    report = Report()
    src = source.load(path, report)
    assert src is not None
    play = parse.parse(src, report)
    assert play is not None
    infos = {
        cue: ClipInfo(ms, ((0, 1, 0), (2, 5, ms // 2)), (("m", 100),), True)
        for cue, ms in clips.items()
    }
    return layout(play, infos, report), report


def _starts(placed: Layout) -> dict[str, tuple[int, int]]:
    return {pl.line.cue: (pl.start, pl.end) for pl in placed.lines}


def test_gap_pause_and_cursor(tmp_path: Path) -> None:
    placed, report = _layout(
        tmp_path,
        """
defaults: {gap: 100ms}
scenes:
  - scene: s
    lines:
      - {a: One., cue: l1}
      - {b: Two., cue: l2}
      - pause: 1s
      - {a: Three., cue: l3, gap: 0ms}
""",
        {"l1": 1000, "l2": 500, "l3": 200},
    )
    assert not report.has_errors
    assert _starts(placed) == {"l1": (0, 1000), "l2": (1100, 1600), "l3": (2600, 2800)}


def test_with_after_overlap_at(tmp_path: Path) -> None:
    placed, _ = _layout(
        tmp_path,
        """
scenes:
  - scene: s
    lines:
      - {a: One., cue: l1}
      - {b: Two., cue: l2, overlap: 300ms}
      - {a: Three., cue: l3, after: l1 + 2s, gap: 50ms}
      - {b: Four., cue: l4, with: previous - 100ms}
      - {a: Five., cue: l5, at: 10s}
""",
        {"l1": 1000, "l2": 500, "l3": 200, "l4": 400, "l5": 100},
    )
    assert _starts(placed) == {
        "l1": (0, 1000),
        "l2": (700, 1200),
        "l3": (3050, 3250),
        "l4": (2950, 3350),
        "l5": (10000, 10100),
    }


def test_overlapping_line_does_not_pull_the_cursor_back(tmp_path: Path) -> None:
    placed, _ = _layout(
        tmp_path,
        """
scenes:
  - scene: s
    lines:
      - {a: Long one., cue: l1}
      - {b: Short., cue: l2, with: previous}
      - {a: Next., cue: l3, gap: 0ms}
""",
        {"l1": 2000, "l2": 300, "l3": 100},
    )
    assert _starts(placed)["l3"] == (2000, 2100)


def test_scenes_follow_each_other_with_their_gap(tmp_path: Path) -> None:
    placed, _ = _layout(
        tmp_path,
        """
defaults: {scene_gap: 2s}
scenes:
  - scene: one
    lines: [{a: One., cue: l1}]
  - scene: two
    gap: 500ms
    lines: [{b: Two., cue: l2}]
  - scene: three
    lines: [{a: Three., cue: l3}]
""",
        {"l1": 1000, "l2": 1000, "l3": 1000},
    )
    assert _starts(placed) == {"l1": (0, 1000), "l2": (1500, 2500), "l3": (4500, 5500)}
    assert placed.scenes == [("one", 0, 1000), ("two", 1500, 2500), ("three", 4500, 5500)]


def test_gesture_anchors(tmp_path: Path) -> None:
    placed, report = _layout(
        tmp_path,
        """
scenes:
  - scene: s
    lines:
      - a: '<speak>Hi <mark name="m"/> there friend</speak>'
        cue: l1
        gestures:
          - {gesture: up, at: word 2, cue: g-word}
          - {gesture: up, at: mark m, robot: b, cue: g-mark}
      - b: Later.
        cue: l2
        gap: 5s
        gestures:
          - {gesture: up, at: end - 100ms, robot: a, cue: g-end}
""",
        {"l1": 1000, "l2": 400},
    )
    assert not report.has_errors, list(report)
    starts = {pm.cue: pm.start for pm in placed.motions}
    # word 2 ("there") is matched to the engine word covering characters 2..5 at 500 ms.
    assert starts == {"g-word": 500, "g-mark": 100, "g-end": 6300}


def test_motion_cue_waits_only_when_asked(tmp_path: Path) -> None:
    placed, _ = _layout(
        tmp_path,
        """
scenes:
  - scene: s
    lines:
      - {robot: a, gesture: up, cue: m1}
      - {b: Meanwhile., cue: l1}
      - {robot: a, gesture: up, cue: m2, wait: true, gap: 0ms}
      - {b: After., cue: l2, gap: 0ms}
""",
        {"l1": 300, "l2": 300},
    )
    motions = {pm.cue: (pm.start, pm.end) for pm in placed.motions}
    # The line after a motion cue keeps its default 250 ms gap; only `wait` moves the cursor.
    assert motions == {"m1": (0, 1000), "m2": (550, 1550)}
    assert _starts(placed) == {"l1": (250, 550), "l2": (1550, 1850)}


def test_poses_carry_from_one_gesture_to_the_next(tmp_path: Path) -> None:
    placed, _ = _layout(
        tmp_path,
        """
scenes:
  - scene: s
    lines:
      - {robot: a, gesture: up, cue: m1, wait: true}
      - {robot: a, gesture: up, cue: m2}
      - {b: Hi., cue: l1}
""",
        {"l1": 300},
    )
    second = next(pm for pm in placed.motions if pm.cue == "m2")
    assert second.expanded is not None
    assert second.expanded.tracks["arm"][0][1] == second.expanded.tracks["arm"][-1][1]
