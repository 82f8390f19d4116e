"""Offline voice lists for lint: eSpeak NG's data directory and Polly's service model.

Nothing here imports boto3, botocore or the audio stack: the eSpeak list comes from
the file names in the `espeakng-loader` wheel, and the Polly list from the VoiceId
enum in botocore's bundled service model, read as a (gzipped) JSON file.
"""

from __future__ import annotations

import functools
import gzip
import importlib.util
import json
from pathlib import Path


def _package_dir(name: str) -> Path | None:
    spec = importlib.util.find_spec(name)
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(next(iter(spec.submodule_search_locations)))


def espeak_data_dir() -> Path | None:
    pkg = _package_dir("espeakng_loader")
    if pkg is None:
        return None
    data = pkg / "espeak-ng-data"
    return data if data.is_dir() else None


@functools.cache
def _espeak_table() -> tuple[frozenset[str], dict[str, str]]:
    """Voice file names (what `espeak_SetVoiceByName` accepts) and language code -> file."""
    data = espeak_data_dir()
    if data is None:
        return frozenset(), {}
    files: set[str] = set()
    best: dict[str, tuple[int, str]] = {}
    for f in sorted((data / "lang").rglob("*")):
        if not f.is_file():
            continue
        name = f.name.lower()
        files.add(name)
        try:
            text = f.read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue
        for line in text.splitlines():
            parts = line.split()
            if len(parts) >= 2 and parts[0] == "language":
                priority = int(parts[2]) if len(parts) > 2 and parts[2].isdigit() else 5
                code = parts[1].lower()
                if code not in best or priority < best[code][0]:
                    best[code] = (priority, name)
    return frozenset(files), {code: name for code, (_, name) in best.items()}


def espeak_languages() -> frozenset[str]:
    """Every voice name or language code eSpeak NG can speak (lower case)."""
    files, codes = _espeak_table()
    return files | frozenset(codes)


def espeak_resolve(voice: str) -> str | None:
    """The name `espeak_SetVoiceByName` accepts for `voice` (`en-gb` -> `en`), or None."""
    lang, plus, variant = voice.partition("+")
    files, codes = _espeak_table()
    low = lang.lower()
    name = low if low in files else codes.get(low)
    if name is None or (variant and variant not in espeak_variants()):
        return None
    return name + plus + variant


@functools.cache
def espeak_variants() -> frozenset[str]:
    data = espeak_data_dir()
    if data is None:
        return frozenset()
    return frozenset(f.name for f in (data / "voices" / "!v").iterdir() if f.is_file())


def espeak_voice_ok(voice: str) -> str | None:
    """None if eSpeak NG knows `voice` (`lang` or `lang+variant`), else what is wrong."""
    lang, _, variant = voice.partition("+")
    if lang.lower() not in espeak_languages():
        return f"eSpeak NG has no language voice {lang!r}"
    if variant and variant not in espeak_variants():
        return f"eSpeak NG has no voice variant {variant!r}"
    return None


@functools.cache
def _polly_model() -> dict[str, object]:
    pkg = _package_dir("botocore")
    if pkg is None:
        return {}
    for version_dir in sorted((pkg / "data" / "polly").glob("*"), reverse=True):
        for name in ("service-2.json.gz", "service-2.json"):
            f = version_dir / name
            if f.exists():
                raw = f.read_bytes()
                text = gzip.decompress(raw) if name.endswith(".gz") else raw
                data = json.loads(text)
                shapes = data.get("shapes", {})
                assert isinstance(shapes, dict)
                return shapes
    return {}


def _enum(shape: str) -> frozenset[str]:
    entry = _polly_model().get(shape)
    if isinstance(entry, dict):
        return frozenset(entry.get("enum", ()))
    return frozenset()


def polly_voices() -> frozenset[str]:
    """Polly VoiceId values from botocore's service model."""
    return _enum("VoiceId")


def polly_languages() -> frozenset[str]:
    return _enum("LanguageCode")
