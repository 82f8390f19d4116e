"""A process that initialises eSpeak NG once and forks one child per line.

eSpeak NG keeps state between utterances that no public call resets (seen here:
the same text gives a few samples more or less on each call, even after
`espeak_Terminate`/`espeak_Initialize` and `espeak_ng_SetRandSeed`). A child forked
from a process that has never spoken starts from the same state every time, so
the same line always gives the same bytes. A crash inside the C library only
kills one child, which is reported as that line's error.

Run as `python -m scriptc.voices.espeak_zygote JOBS.json OUTDIR WORKERS`; it prints
`INDEX ok` or `INDEX error MESSAGE` per finished job.
"""

from __future__ import annotations

import ctypes
import json
import os
import sys
import traceback
from typing import Any

AUDIO_OUTPUT_SYNCHRONOUS = 2
INIT_DONT_EXIT = 0x8000
CHARS_UTF8 = 1
SSML = 0x10
POS_CHARACTER = 1
EV_LIST_TERMINATED, EV_WORD, EV_SENTENCE, EV_MARK = 0, 1, 2, 3
PARAM_RATE, PARAM_PITCH = 1, 3


class _Id(ctypes.Union):
    _fields_ = [("number", ctypes.c_int), ("name", ctypes.c_char_p), ("string", ctypes.c_char * 8)]


class Event(ctypes.Structure):
    _fields_ = [
        ("type", ctypes.c_int),
        ("unique_identifier", ctypes.c_uint),
        ("text_position", ctypes.c_int),
        ("length", ctypes.c_int),
        ("audio_position", ctypes.c_int),
        ("sample", ctypes.c_int),
        ("user_data", ctypes.c_void_p),
        ("id", _Id),
    ]


Callback = ctypes.CFUNCTYPE(
    ctypes.c_int, ctypes.POINTER(ctypes.c_short), ctypes.c_int, ctypes.POINTER(Event)
)


def load() -> tuple[Any, int]:
    """Load and initialise the embedded library; return it and its sample rate."""
    import espeakng_loader

    lib = ctypes.CDLL(espeakng_loader.get_library_path())
    lib.espeak_Initialize.restype = ctypes.c_int
    lib.espeak_Info.restype = ctypes.c_char_p
    rate = lib.espeak_Initialize(
        AUDIO_OUTPUT_SYNCHRONOUS, 0, espeakng_loader.get_data_path().encode(), INIT_DONT_EXIT
    )
    if rate <= 0:
        raise RuntimeError("eSpeak NG failed to initialise")
    return lib, rate


def synth(lib: Any, rate: int, job: dict[str, Any]) -> tuple[bytes, dict[str, Any]]:
    chunks: list[bytes] = []
    words: list[list[int]] = []
    marks: list[list[Any]] = []
    text: str = job["text"]
    # eSpeak reports character positions; map them back to Python string indices.

    @Callback  # type: ignore[untyped-decorator]
    def on_audio(wav: Any, n: int, events: Any) -> int:
        if wav and n > 0:
            chunks.append(ctypes.string_at(wav, n * 2))
        i = 0
        while events[i].type != EV_LIST_TERMINATED:
            ev = events[i]
            ms = round(ev.sample * 1000 / rate)
            if ev.type == EV_WORD:
                start = max(0, ev.text_position - 1)
                words.append([start, start + ev.length, ms])
            elif ev.type == EV_MARK and ev.id.name:
                marks.append([ev.id.name.decode("utf-8", "replace"), ms])
            i += 1
        return 0

    lib.espeak_SetSynthCallback(on_audio)
    if lib.espeak_SetVoiceByName(job["voice"].encode()) != 0:
        raise ValueError(f"eSpeak NG has no voice {job['voice']!r}")
    if job.get("rate"):
        lib.espeak_SetParameter(PARAM_RATE, int(job["rate"]), 0)
    if job.get("pitch") is not None:
        lib.espeak_SetParameter(PARAM_PITCH, int(job["pitch"]), 0)
    data = text.encode("utf-8")
    flags = CHARS_UTF8 | (SSML if job.get("ssml") else 0)
    err = lib.espeak_Synth(data, len(data) + 1, 0, POS_CHARACTER, 0, flags, None, None)
    if err != 0 or lib.espeak_Synchronize() != 0:
        raise RuntimeError(f"eSpeak NG could not synthesise this line (error {err})")
    return b"".join(chunks), {"words": words, "marks": marks, "sample_rate": rate}


def _child(lib: Any, rate: int, job: dict[str, Any], out: str, index: int) -> int:
    try:
        pcm, meta = synth(lib, rate, job)
        with open(os.path.join(out, f"{index}.pcm"), "wb") as f:
            f.write(pcm)
        with open(os.path.join(out, f"{index}.json"), "w", encoding="utf-8") as f:
            json.dump(meta, f)
        return 0
    except Exception as exc:  # reported to the parent as this line's error
        with open(os.path.join(out, f"{index}.err"), "w", encoding="utf-8") as f:
            f.write(str(exc) or traceback.format_exc())
        return 1


def main(argv: list[str]) -> int:
    jobs_file, out, workers = argv[0], argv[1], max(1, int(argv[2]))
    with open(jobs_file, encoding="utf-8") as f:
        jobs: list[dict[str, Any]] = json.load(f)
    lib, rate = load()
    running: dict[int, int] = {}
    pending = list(range(len(jobs)))
    pending.reverse()
    while pending or running:
        while pending and len(running) < workers:
            index = pending.pop()
            pid = os.fork()
            if pid == 0:
                os._exit(_child(lib, rate, jobs[index], out, index))
            running[pid] = index
        pid, status = os.wait()
        index = running.pop(pid)
        if os.waitstatus_to_exitcode(status) == 0:
            print(f"{index} ok", flush=True)
        else:
            err = os.path.join(out, f"{index}.err")
            try:
                with open(err, encoding="utf-8") as f:
                    msg = f.read()
            except OSError:
                msg = f"the synthesiser crashed (status {status})"
            print(f"{index} error {json.dumps(msg)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
