"""Turn loaded YAML sources into a `Play`, reporting every problem on the way."""

from __future__ import annotations

from scriptc.diagnostics import Report, Span
from scriptc.model import Play
from scriptc.parse_cast import CastReader, read_defaults
from scriptc.parse_scenes import SceneReader
from scriptc.reader import Reader
from scriptc.source import Map, Scalar, Source, kind_name

PLAY_KEYS = ("title", "include", "defaults", "robots", "gestures", "scenes")
INCLUDE_KEYS = ("include", "robots", "gestures")


def parse(source: Source, report: Report) -> Play | None:
    """Build the play model; None when the main file has no usable top level."""
    reader = Reader(report)
    cast = CastReader(reader)
    main = source.main
    for f in source.files:
        root = f.root
        if root is None or (isinstance(root, Scalar) and root.value is None):
            if f is main and not f.unreadable:
                report.error(
                    Span(f.name, 1, 1),
                    "E013",
                    "the screenplay is empty",
                    "start with `title:`, `robots:` and `scenes:`",
                )
            continue
        if not isinstance(root, Map):
            report.error(
                root.span,
                "E011",
                f"a screenplay must be a mapping, got {kind_name(root)}",
                "start with `title:`, `robots:` and `scenes:`",
            )
            continue
        allowed = PLAY_KEYS if f is main else INCLUDE_KEYS
        reader.unknown_keys(root, "the screenplay" if f is main else "an included file", allowed)
        cast.add_robots(root.get("robots"))
        cast.add_gestures(root.get("gestures"))
    root = main.root
    if not isinstance(root, Map):
        return None
    defaults = read_defaults(reader, root.get("defaults"))
    robots, gestures = cast.freeze()
    if not robots:
        report.error(
            root.key_span("robots") if "robots" in root.entries else root.span,
            "E013",
            "the screenplay defines no robots",
            "add `robots:` with at least one robot",
        )
    title = reader.text(root.get("title"), "title") if root.get("title") is not None else None
    scenes_node = root.get("scenes")
    if scenes_node is None:
        report.error(
            root.span,
            "E013",
            "the screenplay has no `scenes:`",
            "add `scenes:` with at least one scene of lines",
        )
    scenes = SceneReader(reader, set(robots), defaults.gap_ms, defaults.scene_gap_ms).read(
        scenes_node
    )
    return Play(title or main.path.stem, robots, gestures, scenes, defaults, root.span)
