"""Compiler benchmarks, printed side by side in one run.

    python bench/bench_compiler.py            # 500- and 5,000-line plays
    python bench/bench_compiler.py --quick    # smaller, for a smoke run

Figures: lint of a 5,000-line play against yamllint on the same file (both
in-process, ratio), warm rebuild of 500 and 5,000 lines (zero synthesis calls,
in-process), and cold offline build speed as a multiple of real time with the
embedded eSpeak NG voice at --jobs 1 and 2.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from genplay import generate

from scriptc.build import build
from scriptc.lint import lint


def timed(fn: Callable[[], object], repeat: int) -> tuple[float, object]:
    """Median wall time in seconds over `repeat` runs, and the last result.

    Garbage from earlier sections is collected first, so one section's leftovers do not
    slow the next one's cyclic garbage collection.
    """
    gc.collect()
    times, result = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), result


def yamllint_run(path: Path) -> int:
    from yamllint import linter
    from yamllint.config import YamlLintConfig

    conf = YamlLintConfig("extends: relaxed")
    return len(list(linter.run(path.read_text(), conf)))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    small, large = (100, 1000) if args.quick else (500, 5000)
    rows: list[tuple[str, str, str]] = []
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        p_small = generate(small, root / "s")
        p_large = generate(large, root / "l", engine="fixed")
        lines_large = len(p_large.read_text().splitlines())

        # Lint vs yamllint on the same 5,000-line play.
        t_lint, res = timed(lambda: lint(p_large), 3)
        errors = [d for d in res.report if d.severity.name == "ERROR"]  # type: ignore[attr-defined]
        assert not errors, errors[:3]
        del res
        t_yl, _ = timed(lambda: yamllint_run(p_large), 3)
        rows.append(
            (
                f"lint {large} lines ({lines_large} YAML lines)",
                f"{t_lint * 1000:.0f} ms",
                f"yamllint {t_yl * 1000:.0f} ms; scriptc/yamllint = {t_lint / t_yl:.2f}x "
                "(target <= 1.00)",
            )
        )

        # Cold offline build with eSpeak NG, jobs 1 and 2.
        cold = {}
        for jobs in (1, 2):
            t0 = time.perf_counter()
            result = build(p_small, root / f"out{jobs}", cache_dir=root / f"cache{jobs}", jobs=jobs)
            cold[jobs] = time.perf_counter() - t0
            assert result.synthesized == small
            audio_s = (
                sum(a.duration for r in result.timeline.robots.values() for a in r.audio) / 1000
            )
            del result
        rows.append(
            (
                f"cold build {small} lines, espeak, --jobs 1",
                f"{cold[1]:.2f} s",
                f"{audio_s / cold[1]:.0f}x real time ({audio_s:.0f} s of speech)",
            )
        )
        rows.append(
            (
                f"cold build {small} lines, espeak, --jobs 2",
                f"{cold[2]:.2f} s",
                f"{audio_s / cold[2]:.0f}x real time (target >= 200x); "
                f"jobs2/jobs1 speed-up {cold[1] / cold[2]:.2f}x",
            )
        )

        # Warm rebuilds: nothing changed, zero synthesis calls.
        t_warm, res2 = timed(lambda: build(p_small, root / "out2", cache_dir=root / "cache2"), 7)
        assert res2.synthesized == 0  # type: ignore[attr-defined]
        del res2
        t_lint_small, _ = timed(lambda: lint(p_small), 7)
        rows.append(
            (
                f"warm rebuild {small} lines (0 synth calls)",
                f"{t_warm * 1000:.0f} ms",
                f"target <= 150 ms; lint alone {t_lint_small * 1000:.0f} ms "
                f"(rebuild/lint = {t_warm / t_lint_small:.2f}x)",
            )
        )
        build(p_large, root / "outL", cache_dir=root / "cacheL")
        t_warm_l, res3 = timed(lambda: build(p_large, root / "outL", cache_dir=root / "cacheL"), 3)
        assert res3.synthesized == 0  # type: ignore[attr-defined]
        rows.append(
            (
                f"warm rebuild {large} lines (0 synth calls)",
                f"{t_warm_l * 1000:.0f} ms",
                f"lint alone {t_lint * 1000:.0f} ms (rebuild/lint = {t_warm_l / t_lint:.2f}x)",
            )
        )

    width = max(len(r[0]) for r in rows)
    print(f"{'benchmark':<{width}}  {'median':>9}  comparison")
    for name, value, note in rows:
        print(f"{name:<{width}}  {value:>9}  {note}")


if __name__ == "__main__":
    main()
