"""The shipped JSON Schema accepts every valid play and rejects broken ones."""

from __future__ import annotations

import json
from importlib.resources import files
from pathlib import Path

import jsonschema
import pytest
from ruamel.yaml import YAML

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = json.loads((files("scriptc") / "schema" / "screenplay.schema.json").read_text())
VALID = [
    ROOT / "plays" / "einstein.yaml",
    *sorted((ROOT / "plays" / "cast").glob("*.yaml")),
    *sorted((ROOT / "tests" / "golden").rglob("*.yaml")),
]


def _load(path: Path) -> object:
    return YAML(typ="safe").load(path.read_text(encoding="utf-8"))


def test_schema_is_valid() -> None:
    jsonschema.Draft202012Validator.check_schema(SCHEMA)


@pytest.mark.parametrize("path", VALID, ids=lambda p: str(p.relative_to(ROOT)))
def test_valid_plays_validate(path: Path) -> None:
    jsonschema.validate(_load(path), SCHEMA, cls=jsonschema.Draft202012Validator)


@pytest.mark.parametrize(
    "name",
    [
        "unknown-top-key",
        "bad-duration-unit",
        "wrong-type-lines",
        "servo-id-range",
        "bad-baud",
        "bad-angle",
    ],
)
def test_broken_plays_are_rejected(name: str) -> None:
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(
            _load(ROOT / "tests" / "bad" / f"{name}.yaml"),
            SCHEMA,
            cls=jsonschema.Draft202012Validator,
        )
