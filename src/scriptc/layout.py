"""Place every line and gesture on one clock: the time model of the screenplay.

A cursor walks each scene. A line starts at the cursor plus its gap (no gap for a
scene's first item), `with` or `after` an earlier cue, `overlap`ping the end of the
previous line, or `at` an offset from the scene start; it moves the cursor to its
end if that is later. A pause moves the cursor. A gesture-only cue starts like a
line and moves the cursor only with `wait: true`. Gestures attached to a line start
at its start, end, a word, an SSML mark or an offset.

Layout is pure: the play plus the measured (or, for lint, estimated) clips in,
placed items out. It reports placement problems; the timing checks read its result.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from scriptc import anchors
from scriptc.diagnostics import Report, Span, did_you_mean
from scriptc.model import Anchor, Line, Motion, Pause, Placement, Play, Robot
from scriptc.motion import Expanded, expand


@dataclass(frozen=True, slots=True)
class ClipInfo:
    """What layout needs to know about a line's audio."""

    duration_ms: int
    words: tuple[tuple[int, int, int], ...]  # (char start, char end, start ms) per spoken word
    marks: tuple[tuple[str, int], ...]
    exact: bool


def estimate(line: Line) -> ClipInfo:
    """A rough clip for lint when no audio exists: about 170 words a minute."""
    ws = anchors.words(line.text)
    per_word = 350
    pauses = sum(line.text.count(c) for c in ".,;:!?") * 120
    duration = max(400, len(ws) * per_word + pauses)
    step = (duration - pauses) / max(1, len(ws))
    words = tuple((w.start, w.end, round(i * step)) for i, w in enumerate(ws))
    return ClipInfo(duration, words, (), exact=False)


@dataclass(slots=True)
class PlacedLine:
    line: Line
    scene: str
    start: int
    end: int
    info: ClipInfo


@dataclass(slots=True)
class PlacedMotion:
    robot: str
    gesture: str
    cue: str
    scene: str
    start: int
    span: Span
    order: int
    expanded: Expanded | None = None
    start_pose: dict[str, float] = field(default_factory=dict)

    @property
    def end(self) -> int:
        return self.start + (self.expanded.duration_ms if self.expanded else 0)


@dataclass(slots=True)
class Layout:
    lines: list[PlacedLine]
    motions: list[PlacedMotion]
    scenes: list[tuple[str, int, int]]
    exact: bool
    duration: int


def word_time(info: ClipInfo, text: str, anchor: Anchor) -> int | None:
    """Milliseconds into the clip where the anchored word starts, or None if absent."""
    written = anchors.words(text)
    if anchor.index is not None:
        if anchor.index > len(written):
            return None
        target = written[anchor.index - 1]
    else:
        wanted = (anchor.text or "").lower()
        match = [w for w in written if w.text.lower().strip("'’-") == wanted.strip("'’-")]
        if not match:
            return None
        target = match[0]
    best = None
    for start, end, ms in info.words:
        if start <= target.start < max(end, start + 1):
            return ms
        if start <= target.start:
            best = ms
    return best if best is not None else 0


class _Placer:
    def __init__(self, play: Play, clips: Mapping[str, ClipInfo], report: Report) -> None:
        self.play = play
        self.clips = clips
        self.report = report
        self.cues: dict[str, tuple[int, int]] = {}
        self.later: set[str] = {c.cue for c in play.lines()}
        self.lines: list[PlacedLine] = []
        self.motions: list[PlacedMotion] = []

    def _ref(self, placement: Placement, prev: tuple[int, int] | None) -> tuple[int, int] | None:
        assert placement.ref is not None
        name = placement.ref.cue
        if name == "previous":
            if prev is None:
                self.report.error(placement.span, "E024", "there is no previous line to refer to")
            return prev
        if name in self.cues:
            return self.cues[name]
        if name in self.later:
            self.report.error(
                placement.span,
                "E024",
                f"cue {name!r} comes later in the play",
                "a line can only be placed against an earlier cue",
            )
        else:
            self.report.error(
                placement.span,
                "E024",
                f"unknown cue {name!r}",
                did_you_mean(name, self.cues) or "cue ids are set with `cue:`",
            )
        return None

    def place(
        self, p: Placement, cursor: int, scene_start: int, first: bool, prev: tuple[int, int] | None
    ) -> int:
        if p.kind == "gap":
            start = cursor if first else cursor + p.ms
        elif p.kind == "at":
            start = scene_start + p.ms
        elif p.kind == "overlap":
            if prev is None:
                self.report.error(p.span, "E024", "`overlap` needs a previous line")
                start = cursor
            else:
                start = prev[1] - p.ms
        else:
            ref = self._ref(p, prev)
            assert p.ref is not None
            if ref is None:
                start = cursor
            elif p.kind == "with":
                start = ref[0] + p.ref.offset_ms
            else:
                start = ref[1] + p.ms + p.ref.offset_ms
        if start < 0:
            self.report.error(p.span, "E016", f"this starts {-start}ms before the show begins")
            start = 0
        return start

    def anchor_time(self, pl: PlacedLine, a: Anchor) -> int | None:
        if a.kind == "start":
            base: int | None = pl.start
        elif a.kind == "end":
            base = pl.end
        elif a.kind == "time":
            base = pl.start
        elif a.kind == "word":
            t = word_time(pl.info, pl.line.text, a)
            base = None if t is None else pl.start + t
            if base is None:
                what = f"word {a.index}" if a.index is not None else f'word "{a.text}"'
                n = len(anchors.words(pl.line.text))
                self.report.error(
                    a.span,
                    "E050",
                    f"{what} is not in this line ({n} words)",
                    did_you_mean(a.text or "", [w.text for w in anchors.words(pl.line.text)]),
                )
        else:
            found = dict(pl.info.marks)
            if a.text not in found:
                if a.text in anchors.marks(pl.line.text):
                    base = pl.start  # lint estimate: the mark exists but has no time yet
                else:
                    base = None
                    self.report.error(
                        a.span,
                        "E050",
                        f"mark {a.text!r} is not in this line",
                        did_you_mean(a.text or "", anchors.marks(pl.line.text))
                        or 'add <mark name="..."/> to the SSML',
                    )
            else:
                base = pl.start + found[a.text]
        return None if base is None else base + a.offset_ms

    def run(self) -> Layout:
        cursor = 0
        scenes: list[tuple[str, int, int]] = []
        prev: tuple[int, int] | None = None
        order = 0
        for si, scene in enumerate(self.play.scenes):
            scene_start = cursor + (scene.gap_ms if si else 0)
            cursor = scene_start
            first = True
            end_of_scene = scene_start
            for item in scene.items:
                if isinstance(item, Pause):
                    cursor += item.ms
                    end_of_scene = max(end_of_scene, cursor)
                    continue
                start = self.place(item.placement, cursor, scene_start, first, prev)
                first = False
                if isinstance(item, Line):
                    info = self.clips.get(item.cue) or estimate(item)
                    pl = PlacedLine(item, scene.id, start, start + info.duration_ms, info)
                    self.lines.append(pl)
                    self.cues[item.cue] = (pl.start, pl.end)
                    prev = (pl.start, pl.end)
                    cursor = max(cursor, pl.end)
                    end_of_scene = max(end_of_scene, pl.end)
                    for gc in item.gestures:
                        t = self.anchor_time(pl, gc.anchor)
                        if t is None:
                            continue
                        if t < 0:
                            self.report.error(
                                gc.anchor.span, "E016", "this gesture starts before the show"
                            )
                            t = 0
                        order += 1
                        pm = PlacedMotion(
                            gc.robot, gc.gesture, gc.cue or item.cue, scene.id, t, gc.span, order
                        )
                        self.motions.append(pm)
                        end_of_scene = max(end_of_scene, self._measure(pm))
                        if gc.cue:
                            self.cues[gc.cue] = (pm.start, pm.end)
                elif isinstance(item, Motion):
                    order += 1
                    pm = PlacedMotion(
                        item.robot, item.gesture, item.cue, scene.id, start, item.span, order
                    )
                    self.motions.append(pm)
                    end = self._measure(pm)
                    self.cues[item.cue] = (start, end)
                    end_of_scene = max(end_of_scene, end)
                    if item.wait:
                        cursor = max(cursor, end)
            scenes.append((scene.id, scene_start, end_of_scene))
            cursor = max(cursor, end_of_scene)
        self._poses()
        exact = all(pl.info.exact for pl in self.lines)
        return Layout(self.lines, self.motions, scenes, exact, cursor)

    def _measure(self, pm: PlacedMotion) -> int:
        robot = self.play.robots.get(pm.robot)
        gesture = self.play.gestures.get(pm.gesture)
        if robot is None or gesture is None:
            return pm.start
        home = {j.name: j.home for j in robot.joints.values()}
        pm.expanded = expand(gesture, robot.joints, home)
        return pm.end

    def _poses(self) -> None:
        """Re-expand each robot's gestures in time order from the pose the last one left."""
        by_robot: dict[str, list[PlacedMotion]] = {}
        for pm in self.motions:
            by_robot.setdefault(pm.robot, []).append(pm)
        for name, motions in by_robot.items():
            robot: Robot | None = self.play.robots.get(name)
            if robot is None:
                continue
            pose = {j.name: j.home for j in robot.joints.values()}
            for pm in sorted(motions, key=lambda m: (m.start, m.order)):
                gesture = self.play.gestures.get(pm.gesture)
                if gesture is None:
                    continue
                pm.start_pose = dict(pose)
                pm.expanded = expand(gesture, robot.joints, pose)
                pose.update(pm.expanded.end_pose)


def layout(play: Play, clips: Mapping[str, ClipInfo], report: Report) -> Layout:
    """Place every item of `play`; `clips` maps line cue ids to their measured audio."""
    return _Placer(play, clips, report).run()
