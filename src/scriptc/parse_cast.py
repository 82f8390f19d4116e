"""Read the cast: defaults, robots (voices, bus, joints) and the gesture library.

Robots and gestures may come from several files (the play and its includes). A
robot's parts (`voice`, `bus`, `joints`) merge across files; defining the same
part or the same gesture twice is an error that names both places.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from scriptc.diagnostics import Span
from scriptc.model import (
    EASES,
    Bus,
    Defaults,
    Gesture,
    Joint,
    Keyframe,
    PollySettings,
    Robot,
    Target,
    Voice,
)
from scriptc.reader import Reader
from scriptc.source import Map, Node, Scalar

ROBOT_KEYS = ("voice", "bus", "joints")
BUS_KEYS = ("port", "baud", "protocol", "model")
JOINT_KEYS = ("id", "min", "max", "home", "max_speed")
VOICE_KEYS = ("id", "lang", "engine", "rate", "pitch", "wpm")
GESTURE_KEYS = ("keyframes", "loop", "repeat", "then", "return")
DEFAULT_KEYS = ("gap", "scene_gap", "engine", "polly")
POLLY_KEYS = ("engine", "format", "sample_rate", "lexicons", "region")
POLLY_ENGINES = ("standard", "neural", "long-form", "generative")
POLLY_FORMATS = {
    "pcm": (8000, 16000),
    "mp3": (8000, 16000, 22050, 24000),
    "ogg_vorbis": (8000, 16000, 22050, 24000),
}
BAUD_RATES = (9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000, 4500000)
SERVO_MODELS = {1: ("ax12", "mx28-p1"), 2: ("xm430", "xl430", "mx28", "mx64", "xm540")}


def read_defaults(reader: Reader, node: Node | None) -> Defaults:
    m = reader.map(node, "defaults", DEFAULT_KEYS)
    if m is None:
        return Defaults()
    d = Defaults()
    gap = reader.duration(m.get("gap"), "default gap")
    scene_gap = reader.duration(m.get("scene_gap"), "scene gap")
    engine = reader.text(m.get("engine"), "default engine")
    return Defaults(
        gap_ms=d.gap_ms if gap is None else gap,
        scene_gap_ms=d.scene_gap_ms if scene_gap is None else scene_gap,
        engine=engine or d.engine,
        polly=_read_polly(reader, m.get("polly")),
    )


def _read_polly(reader: Reader, node: Node | None) -> PollySettings:
    m = reader.map(node, "polly settings", POLLY_KEYS)
    base = PollySettings()
    if m is None:
        return base
    engine = reader.choice(m.get("engine"), "Polly engine", POLLY_ENGINES) or base.engine
    fmt = reader.choice(m.get("format"), "Polly format", tuple(POLLY_FORMATS)) or base.format
    rate = reader.integer(m.get("sample_rate"), "Polly sample rate", 8000, 24000)
    if rate is None:
        rate = 16000 if fmt == "pcm" else 24000
    elif rate not in POLLY_FORMATS[fmt]:
        allowed = ", ".join(str(r) for r in POLLY_FORMATS[fmt])
        reader.report.error(
            reader.span_of(m.get("sample_rate"), m.span),
            "E012",
            f"Polly {fmt} output supports sample rates {allowed}, not {rate}",
        )
    lexicons = tuple(
        t
        for t in (reader.text(n, "lexicon name") for n in reader.seq(m.get("lexicons"), "lexicons"))
        if t is not None
    )
    region = reader.text(m.get("region"), "AWS region")
    return PollySettings(engine, fmt, rate, lexicons, region)


@dataclass
class _RobotParts:
    span: Span
    parts: dict[str, tuple[Span, object]] = field(default_factory=dict)


class CastReader:
    """Accumulates robots and gestures from each file, then freezes them."""

    def __init__(self, reader: Reader) -> None:
        self.r = reader
        self.robots: dict[str, _RobotParts] = {}
        self.gestures: dict[str, Gesture] = {}

    def add_robots(self, node: Node | None) -> None:
        m = self.r.map(node, "robots")
        if m is None:
            return
        for name, (knode, value) in m.entries.items():
            rm = self.r.map(value, f"robot {name!r}", ROBOT_KEYS)
            if value is not None and isinstance(value, Scalar) and value.value is None:
                rm = Map(value.span)
            if rm is None:
                continue
            parts = self.robots.setdefault(name, _RobotParts(knode.span))
            for key, (pk, pv) in rm.entries.items():
                if key not in ROBOT_KEYS:
                    continue
                if key in parts.parts:
                    first = parts.parts[key][0]
                    self.r.report.error(
                        pk.span,
                        "E014",
                        f"robot {name!r} already has `{key}`",
                        f"first defined at {first}",
                    )
                    continue
                parsed: object
                if key == "voice":
                    parsed = self._voices(name, pv)
                elif key == "bus":
                    parsed = self._bus(name, pv)
                else:
                    parsed = self._joints(name, pv)
                parts.parts[key] = (pk.span, parsed)

    def _voices(self, robot: str, node: Node) -> dict[str, Voice]:
        m = self.r.map(node, f"voice of {robot!r}")
        voices: dict[str, Voice] = {}
        if m is None:
            return voices
        for engine, (_, value) in m.entries.items():
            if isinstance(value, Map):
                self.r.unknown_keys(value, f"{engine} voice of {robot!r}", VOICE_KEYS)
                vid = self.r.text(
                    self.r.require(value, "id", f"{engine} voice", "id: Matthew"), "voice id"
                )
                lang = self.r.text(value.get("lang"), "voice language")
                opts: list[tuple[str, str | int | float]] = []
                for opt in ("engine", "rate", "pitch", "wpm"):
                    ov = value.get(opt)
                    if (
                        isinstance(ov, Scalar)
                        and isinstance(ov.value, (str, int, float))
                        and not isinstance(ov.value, bool)
                    ):
                        opts.append((opt, ov.value))
                    elif ov is not None:
                        self.r.report.error(
                            ov.span, "E011", f"voice option {opt!r} must be a single value"
                        )
                if vid is not None:
                    voices[engine] = Voice(engine, vid, value.span, lang, tuple(opts))
            else:
                vid = self.r.text(value, f"{engine} voice of {robot!r}")
                if vid is not None:
                    voices[engine] = Voice(engine, vid, value.span)
        return voices

    def _bus(self, robot: str, node: Node) -> Bus | None:
        m = self.r.map(node, f"bus of {robot!r}", BUS_KEYS)
        if m is None:
            return None
        port = self.r.text(self.r.require(m, "port", "a bus", "port: /dev/ttyUSB0"), "bus port")
        baud = 1000000
        if m.get("baud") is not None:
            b = self.r.integer(m.get("baud"), "baud rate", 1, 10_000_000)
            if b is not None and b not in BAUD_RATES:
                self.r.report.error(
                    self.r.span_of(m.get("baud"), m.span),
                    "E012",
                    f"{b} is not a Dynamixel baud rate",
                    "use one of " + ", ".join(str(x) for x in BAUD_RATES),
                )
            baud = b or baud
        protocol = 2
        if m.get("protocol") is not None:
            p = self.r.integer(m.get("protocol"), "protocol", 1, 2)
            protocol = p or protocol
        models = SERVO_MODELS[protocol]
        model = (
            self.r.choice(m.get("model"), f"servo model for protocol {protocol}", models)
            if m.get("model") is not None
            else models[0]
        )
        if port is None:
            return None
        return Bus(port, baud, protocol, model or models[0], m.span)

    def _joints(self, robot: str, node: Node) -> dict[str, Joint]:
        m = self.r.map(node, f"joints of {robot!r}")
        joints: dict[str, Joint] = {}
        if m is None:
            return joints
        ids: dict[int, str] = {}
        for name, (knode, value) in m.entries.items():
            jm = self.r.map(value, f"joint {name!r}", JOINT_KEYS)
            if jm is None:
                continue
            what = f"joint {name!r}"
            jid = self.r.integer(self.r.require(jm, "id", what, "id: 1"), "servo id", 0, 252)
            lo = self.r.angle(jm.get("min"), "minimum angle")
            hi = self.r.angle(jm.get("max"), "maximum angle")
            home = self.r.angle(jm.get("home"), "home angle")
            speed = self.r.speed(jm.get("max_speed"), "max speed")
            lo = -math.pi if lo is None else lo
            hi = math.pi if hi is None else hi
            home = 0.0 if home is None else home
            if lo >= hi:
                self.r.report.error(
                    jm.span, "E012", f"{what} has min {lo:.3f} rad not below max {hi:.3f} rad"
                )
            elif not lo <= home <= hi:
                self.r.report.error(
                    self.r.span_of(jm.get("home"), jm.span),
                    "E030",
                    f"home of {what} is outside its limits",
                    f"limits are {math.degrees(lo):.1f}deg to {math.degrees(hi):.1f}deg",
                )
            if jid is None:
                continue
            if jid in ids:
                self.r.report.error(
                    self.r.span_of(jm.get("id"), jm.span),
                    "E014",
                    f"servo id {jid} is used by joints {ids[jid]!r} and {name!r}",
                )
            ids[jid] = name
            joints[name] = Joint(name, jid, lo, hi, home, speed, knode.span)
        return joints

    def add_gestures(self, node: Node | None) -> None:
        m = self.r.map(node, "gestures")
        if m is None:
            return
        for name, (knode, value) in m.entries.items():
            if name in self.gestures:
                first = self.gestures[name].span
                self.r.report.error(
                    knode.span,
                    "E014",
                    f"gesture {name!r} is defined twice",
                    f"first defined at {first}",
                )
                continue
            g = self._gesture(name, knode.span, value)
            if g is not None:
                self.gestures[name] = g

    def _gesture(self, name: str, span: Span, node: Node) -> Gesture | None:
        gm = self.r.map(node, f"gesture {name!r}", GESTURE_KEYS)
        if gm is None:
            return None
        keyframes = self._keyframes(name, gm.get("keyframes"), "keyframes")
        loop = self._keyframes(name, gm.get("loop"), "loop")
        if not keyframes and not loop:
            self.r.report.error(
                gm.span,
                "E013",
                f"gesture {name!r} has no keyframes",
                "add `keyframes:` with at least one `{at: 500ms, joint: 30deg}`",
            )
            return None
        repeat = 1
        if gm.get("repeat") is not None:
            repeat = self.r.integer(gm.get("repeat"), "repeat", 1, 1000) or 1
        then = "home"
        if gm.get("then") is not None:
            then = self.r.choice(gm.get("then"), "then", ("home", "hold")) or "home"
        ret = self.r.duration(gm.get("return"), "return time")
        return Gesture(name, tuple(keyframes), tuple(loop), repeat, then, ret, span)

    def _keyframes(self, gesture: str, node: Node | None, what: str) -> list[Keyframe]:
        frames: list[Keyframe] = []
        last = -1
        for item in self.r.seq(node, f"{what} of {gesture!r}"):
            km = self.r.map(item, "a keyframe")
            if km is None:
                continue
            at = self.r.duration(
                self.r.require(km, "at", "a keyframe", "at: 400ms"), "keyframe time"
            )
            ease = "linear"
            if km.get("ease") is not None:
                ease = self.r.choice(km.get("ease"), "ease", EASES) or "linear"
            targets = []
            for joint, (jk, jv) in km.entries.items():
                if joint in ("at", "ease"):
                    continue
                rad = self.r.angle(jv, f"target of {joint!r}")
                if rad is not None:
                    targets.append(Target(joint, rad, jk.span))
            if at is None:
                continue
            if at <= last:
                self.r.report.error(
                    self.r.span_of(km.get("at"), km.span),
                    "E012",
                    f"keyframe at {at}ms is not after the one before ({last}ms)",
                    "keyframe times must increase",
                )
            last = max(last, at)
            if not targets:
                self.r.report.warning(km.span, "W012", "keyframe moves no joint")
            frames.append(Keyframe(at, tuple(targets), ease, km.span))
        return frames

    def freeze(self) -> tuple[dict[str, Robot], dict[str, Gesture]]:
        robots: dict[str, Robot] = {}
        for name, parts in self.robots.items():
            voice = parts.parts.get("voice", (parts.span, {}))[1]
            bus = parts.parts.get("bus", (parts.span, None))[1]
            joints = parts.parts.get("joints", (parts.span, {}))[1]
            assert isinstance(voice, dict) and isinstance(joints, dict)
            assert bus is None or isinstance(bus, Bus)
            robots[name] = Robot(name, parts.span, voice, bus, joints)
        return robots, dict(self.gestures)
