"""The embedded default voice: eSpeak NG from the `espeakng-loader` wheel, via ctypes.

No apt package and no network. Each line is synthesised in a child forked from a
pristine eSpeak process (see `espeak_zygote`), `workers` at a time, so output is
byte-for-byte repeatable and a C-level crash costs one line, not the build.
"""

from __future__ import annotations

import functools
import json
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from importlib.metadata import version
from pathlib import Path

from scriptc.audio import wav_bytes
from scriptc.model import PollySettings, Voice
from scriptc.voices import catalog
from scriptc.voices.base import OnDone, Synthesized, SynthJob, VoiceError, VoiceInfo

DEFAULT_VOICE = "en-us"


@functools.cache
def _wheel_version() -> str:
    """The espeakng-loader wheel pins the library and its data: its version keys the cache."""
    return version("espeakng-loader")


class EspeakBackend:
    name = "espeak"

    def identity(self) -> dict[str, str]:
        return {"engine": "espeak-ng", "version": _wheel_version()}

    def job(
        self, cue: str, text: str, ssml: bool, voice: Voice | None, polly: PollySettings
    ) -> SynthJob:
        vid = voice.id if voice else DEFAULT_VOICE
        opts = dict(voice.options) if voice else {}
        settings = tuple(sorted((k, v) for k, v in opts.items() if k in ("rate", "pitch")))
        return SynthJob(cue, text, ssml, vid, voice.lang if voice else None, settings)

    def synthesize(self, jobs: Sequence[SynthJob], *, workers: int, on_done: OnDone) -> None:
        if not jobs:
            return
        for job in jobs:
            problem = catalog.espeak_voice_ok(job.voice)
            if problem:
                raise VoiceError(problem, cue=job.cue, hint="run `scriptc voices --engine espeak`")
        with tempfile.TemporaryDirectory(prefix="scriptc-espeak-") as tmp:
            spec = Path(tmp) / "jobs.json"
            spec.write_text(
                json.dumps(
                    [
                        {
                            "text": j.text,
                            "ssml": j.ssml,
                            "voice": catalog.espeak_resolve(j.voice),
                            **dict(j.settings),
                        }
                        for j in jobs
                    ]
                ),
                encoding="utf-8",
            )
            proc = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "scriptc.voices.espeak_zygote",
                    str(spec),
                    tmp,
                    str(workers),
                ],
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
            )
            assert proc.stdout is not None
            failure: VoiceError | None = None
            for raw in proc.stdout:
                index_text, status, *rest = raw.rstrip("\n").split(" ", 2)
                job = jobs[int(index_text)]
                if status != "ok":
                    why = json.loads(rest[0]) if rest else status
                    failure = failure or VoiceError(
                        f"eSpeak NG failed on line {job.cue}: {why}",
                        cue=job.cue,
                    )
                    continue
                base = Path(tmp) / index_text
                meta = json.loads(base.with_suffix(".json").read_text(encoding="utf-8"))
                pcm = base.with_suffix(".pcm").read_bytes()
                on_done(
                    job,
                    Synthesized(
                        wav_bytes(pcm, int(meta["sample_rate"])),
                        tuple((int(a), int(b), int(c)) for a, b, c in meta["words"]),
                        tuple((str(n), int(t)) for n, t in meta["marks"]),
                    ),
                )
            stderr = proc.stderr.read() if proc.stderr else ""
            if proc.wait() != 0 and failure is None:
                failure = VoiceError(f"the eSpeak NG process failed: {stderr.strip()[-500:]}")
            if failure:
                raise failure

    def voices(self) -> list[VoiceInfo]:
        return [VoiceInfo(name, name) for name in sorted(catalog.espeak_languages())]
