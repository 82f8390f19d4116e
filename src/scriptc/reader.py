"""Typed access to positioned YAML nodes that reports, rather than raises, on bad input.

Each getter returns a value or None; when it returns None a diagnostic with the
node's position has already gone into the report.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from typing import TypeVar

from scriptc import units
from scriptc.diagnostics import Report, Span, did_you_mean, known
from scriptc.source import Map, Node, Scalar, Seq, kind_name

T = TypeVar("T")


class Reader:
    """Reads values from nodes into a `Report`."""

    def __init__(self, report: Report) -> None:
        self.report = report

    def map(
        self, node: Node | None, what: str, allowed: Collection[str] | None = None
    ) -> Map | None:
        if node is None:
            return None
        if not isinstance(node, Map):
            self.report.error(
                node.span,
                "E011",
                f"{what} must be a mapping, got {kind_name(node)}",
                "write it as `key: value` lines",
            )
            return None
        if allowed is not None:
            self.unknown_keys(node, what, allowed)
        return node

    def unknown_keys(self, node: Map, what: str, allowed: Collection[str]) -> None:
        for key, (knode, _) in node.entries.items():
            if key not in allowed:
                hint = did_you_mean(key, allowed) or known(allowed)
                self.report.warning(knode.span, "W010", f"unknown key {key!r} in {what}", hint)

    def seq(self, node: Node | None, what: str) -> list[Node]:
        if node is None:
            return []
        if not isinstance(node, Seq):
            self.report.error(
                node.span,
                "E011",
                f"{what} must be a list, got {kind_name(node)}",
                "write each entry on its own `- ` line",
            )
            return []
        return node.items

    def require(self, node: Map, key: str, what: str, example: str) -> Node | None:
        value = node.get(key)
        if value is None:
            self.report.error(
                node.span, "E013", f"{what} needs `{key}`", f"for example `{example}`"
            )
        return value

    def text(self, node: Node | None, what: str, *, empty_ok: bool = False) -> str | None:
        if node is None:
            return None
        if isinstance(node, Scalar) and isinstance(node.value, str):
            if not empty_ok and not node.value.strip():
                self.report.error(node.span, "E012", f"{what} is empty")
                return None
            return node.value
        if (
            isinstance(node, Scalar)
            and isinstance(node.value, (int, float))
            and not isinstance(node.value, bool)
        ):
            return str(node.value)
        self.report.error(node.span, "E011", f"{what} must be text, got {kind_name(node)}")
        return None

    def integer(self, node: Node | None, what: str, lo: int, hi: int) -> int | None:
        if node is None:
            return None
        if (
            not isinstance(node, Scalar)
            or isinstance(node.value, bool)
            or not isinstance(node.value, int)
        ):
            self.report.error(
                node.span, "E011", f"{what} must be a whole number, got {kind_name(node)}"
            )
            return None
        if not lo <= node.value <= hi:
            self.report.error(
                node.span, "E012", f"{what} must be between {lo} and {hi}, got {node.value}"
            )
            return None
        return node.value

    def boolean(self, node: Node | None, what: str) -> bool | None:
        if node is None:
            return None
        if isinstance(node, Scalar) and isinstance(node.value, bool):
            return node.value
        self.report.error(node.span, "E011", f"{what} must be true or false, got {kind_name(node)}")
        return None

    def choice(self, node: Node | None, what: str, choices: Collection[str]) -> str | None:
        value = self.text(node, what)
        if value is None or node is None:
            return None
        if value not in choices:
            self.report.error(
                node.span,
                "E012",
                f"{what} must be one of {', '.join(choices)}, got {value!r}",
                did_you_mean(value, choices),
            )
            return None
        return value

    def _unit(self, node: Node | None, what: str, parse: Callable[[object], T]) -> T | None:
        if node is None:
            return None
        if not isinstance(node, Scalar):
            self.report.error(
                node.span, "E011", f"{what} must be a single value, got {kind_name(node)}"
            )
            return None
        try:
            return parse(node.value)
        except units.UnitError as exc:
            self.report.error(node.span, "E012", f"bad {what}: {exc}")
            return None

    def duration(self, node: Node | None, what: str) -> int | None:
        return self._unit(node, what, units.duration_ms)

    def angle(self, node: Node | None, what: str) -> float | None:
        return self._unit(node, what, units.angle_rad)

    def speed(self, node: Node | None, what: str) -> float | None:
        return self._unit(node, what, units.speed_rad_s)

    def span_of(self, node: Node | None, fallback: Span) -> Span:
        return node.span if node is not None else fallback
