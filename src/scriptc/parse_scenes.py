"""Read the scenes: lines, pauses and gesture-only cues, with their placement and anchors.

A line is a mapping whose one non-reserved key names the speaking robot and whose
value is the text (SSML when it starts with `<speak`). Each line and gesture-only
cue gets a cue id: the `cue:` it names, or `SCENE/N` counting from 1 in its scene.
"""

from __future__ import annotations

from scriptc import anchors
from scriptc.diagnostics import Span, did_you_mean, known
from scriptc.model import Anchor, GestureCue, Item, Line, Motion, Pause, Placement, Ref, Scene
from scriptc.reader import Reader
from scriptc.source import Map, Node, Scalar, kind_name

SCENE_KEYS = ("scene", "gap", "lines")
PLACEMENT_KEYS = ("gap", "with", "after", "overlap", "at")
LINE_KEYS = ("cue", *PLACEMENT_KEYS, "gesture", "gestures")
MOTION_KEYS = ("robot", "gesture", "cue", "wait", *PLACEMENT_KEYS)
CUE_GESTURE_KEYS = ("gesture", "at", "robot", "cue")


class SceneReader:
    def __init__(self, reader: Reader, robots: set[str], default_gap: int, scene_gap: int) -> None:
        self.r = reader
        self.robots = robots
        self.default_gap = default_gap
        self.scene_gap = scene_gap
        self.cues: dict[str, Span] = {}
        self.scene_ids: dict[str, Span] = {}

    def read(self, node: Node | None) -> tuple[Scene, ...]:
        scenes = []
        for i, item in enumerate(self.r.seq(node, "scenes"), start=1):
            scene = self._scene(item, i)
            if scene is not None:
                scenes.append(scene)
        return tuple(scenes)

    def _cue_id(self, node: Node | None, default: str, span: Span) -> str:
        if node is None:
            cue = default
        else:
            cue = self.r.text(node, "cue id") or default
            span = node.span
        if cue in self.cues:
            self.r.report.error(
                span, "E014", f"cue id {cue!r} is used twice", f"first used at {self.cues[cue]}"
            )
        else:
            self.cues[cue] = span
        return cue

    def _scene(self, node: Node, index: int) -> Scene | None:
        m = self.r.map(node, "a scene", SCENE_KEYS)
        if m is None:
            return None
        sid = self.r.text(m.get("scene"), "scene id") if m.get("scene") is not None else None
        sid = sid or f"scene{index}"
        if sid in self.scene_ids:
            self.r.report.error(
                m.key_span("scene"),
                "E014",
                f"scene {sid!r} is defined twice",
                f"first defined at {self.scene_ids[sid]}",
            )
        self.scene_ids[sid] = m.span
        gap = self.r.duration(m.get("gap"), "scene gap")
        items: list[Item] = []
        n = 0
        for item_node in self.r.seq(m.get("lines"), f"lines of scene {sid!r}"):
            im = self.r.map(item_node, "a line")
            if im is None:
                continue
            if "pause" in im.entries:
                self.r.unknown_keys(im, "a pause", ("pause",))
                ms = self.r.duration(im.get("pause"), "pause")
                if ms is not None:
                    items.append(Pause(ms, im.span))
                continue
            n += 1
            parsed = self._motion(im, sid, n) if self._is_motion(im) else self._line(im, sid, n)
            if parsed is not None:
                items.append(parsed)
        return Scene(sid, tuple(items), self.scene_gap if gap is None else gap, m.span)

    def _is_motion(self, m: Map) -> bool:
        return "robot" in m.entries or (
            "gesture" in m.entries and not any(k not in LINE_KEYS for k in m.entries)
        )

    def _placement(self, m: Map, default_gap: int) -> Placement:
        given = [k for k in ("with", "after", "overlap", "at") if k in m.entries]
        for extra in given[1:]:
            self.r.report.error(
                m.key_span(extra),
                "E015",
                f"`{given[0]}` and `{extra}` both place this line",
                "use one of with, after, overlap or at",
            )
        gap_node = m.get("gap")
        gap = self.r.duration(gap_node, "gap")
        if given and given[0] in ("with", "overlap", "at") and gap_node is not None:
            self.r.report.warning(m.key_span("gap"), "W015", f"`gap` is ignored with `{given[0]}`")
        gap = default_gap if gap is None else gap
        if not given:
            return Placement("gap", gap, m.span)
        kind = given[0]
        node = m.get(kind)
        assert node is not None
        if kind in ("overlap", "at"):
            ms = self.r.duration(node, kind)
            return Placement("overlap" if kind == "overlap" else "at", ms or 0, node.span)
        try:
            cue, offset = anchors.parse_ref(node.value if isinstance(node, Scalar) else None)
        except anchors.AnchorError as exc:
            self.r.report.error(node.span, "E012", str(exc), "for example `with: previous + 300ms`")
            return Placement("gap", gap, m.span)
        ms = gap if kind == "after" else 0
        return Placement(
            "with" if kind == "with" else "after", ms, node.span, Ref(cue, offset, node.span)
        )

    def _line(self, m: Map, scene: str, n: int) -> Line | None:
        speakers = [k for k in m.entries if k not in LINE_KEYS]
        if not speakers:
            self.r.report.error(
                m.span, "E013", "line has no speaker", "write `- robot_name: text of the line`"
            )
            return None
        # The speaker is the first key naming a known robot; failing that, the first
        # unreserved key is taken as a misspelt robot and any other as a misspelt key.
        known_speaker = next((k for k in speakers if k in self.robots), None)
        robot = known_speaker or speakers[0]
        for key in speakers:
            if key == robot and known_speaker is not None:
                continue
            kspan = m.key_span(key)
            if key == robot:
                hint = did_you_mean(key, [*self.robots, *LINE_KEYS]) or known(self.robots)
                self.r.report.error(kspan, "E020", f"unknown robot {key!r}", hint)
            else:
                hint = did_you_mean(key, [*LINE_KEYS, *self.robots]) or known(LINE_KEYS)
                self.r.report.error(kspan, "E010", f"unknown key {key!r} in a line", hint)
        value = m.get(robot)
        assert value is not None
        text = self.r.text(value, f"text of {robot}'s line")
        cue = self._cue_id(m.get("cue"), f"{scene}/{n}", m.span)
        placement = self._placement(m, self.default_gap)
        gestures = self._gesture_cues(m, robot)
        if text is None:
            return None
        ssml = text.lstrip().startswith("<speak")
        return Line(robot, text.strip(), ssml, cue, placement, tuple(gestures), m.span, value.span)

    def _gesture_cues(self, m: Map, robot: str) -> list[GestureCue]:
        cues: list[GestureCue] = []
        single = m.get("gesture")
        if single is not None:
            name = self.r.text(single, "gesture name")
            if name:
                cues.append(GestureCue(name, robot, Anchor("start", 0, single.span), single.span))
        for node in self.r.seq(m.get("gestures"), "gestures"):
            if isinstance(node, Scalar):
                name = self.r.text(node, "gesture name")
                if name:
                    cues.append(GestureCue(name, robot, Anchor("start", 0, node.span), node.span))
                continue
            gm = self.r.map(node, "a gesture cue", CUE_GESTURE_KEYS)
            if gm is None:
                continue
            name = self.r.text(
                self.r.require(gm, "gesture", "a gesture cue", "gesture: wave"), "gesture name"
            )
            who = self.r.text(gm.get("robot"), "robot") or robot
            anchor = Anchor("start", 0, gm.span)
            at = gm.get("at")
            if at is not None:
                if not isinstance(at, Scalar):
                    self.r.report.error(
                        at.span, "E011", f"`at` must be a single value, got {kind_name(at)}"
                    )
                else:
                    try:
                        p = anchors.parse_anchor(at.value)
                        anchor = Anchor(p.kind, p.offset_ms, at.span, p.index, p.text)  # type: ignore[arg-type]
                    except anchors.AnchorError as exc:
                        self.r.report.error(at.span, "E012", str(exc))
            cue = self.r.text(gm.get("cue"), "cue id") if gm.get("cue") is not None else None
            if cue is not None:
                self._cue_id(gm.get("cue"), cue, gm.span)
            if name:
                cues.append(GestureCue(name, who, anchor, gm.span, cue))
        return cues

    def _motion(self, m: Map, scene: str, n: int) -> Motion | None:
        self.r.unknown_keys(m, "a gesture cue", MOTION_KEYS)
        robot = self.r.text(self.r.require(m, "robot", "a gesture-only cue", "robot: dim"), "robot")
        gesture = self.r.text(
            self.r.require(m, "gesture", "a gesture-only cue", "gesture: wave"), "gesture name"
        )
        cue = self._cue_id(m.get("cue"), f"{scene}/{n}", m.span)
        placement = self._placement(m, 0)
        wait = self.r.boolean(m.get("wait"), "wait") or False
        if robot is None or gesture is None:
            return None
        if robot not in self.robots:
            self.r.report.error(
                self.r.span_of(m.get("robot"), m.span),
                "E020",
                f"unknown robot {robot!r}",
                did_you_mean(robot, self.robots) or known(self.robots),
            )
        return Motion(robot, gesture, cue, placement, wait, m.span)
