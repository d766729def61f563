"""Cost of grading a code exercise (200 examples, sandboxed).

1. Whole process: median wall time of `slamcourse check <code exercise> --file <solution>` as a
   ratio to `python -c "import numpy, hypothesis"` in the same venv and run (target ≤ 1.5×).
2. Inside a running engine (as the browser will use it): latency of repeated checks with a
   pre-started worker (target p50 ≤ 150 ms). The learner edits between checks; a short pause
   (not timed) stands in for that.

    python benchmarks/code_check.py [--runs 11] [--repeats 15] [--exercise ID --file PATH]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

from _common import BIN, REPO, environment, interleaved, report

DEFAULT = "observation/observation-model"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=11)
    parser.add_argument("--repeats", type=int, default=15)
    parser.add_argument("--exercise", default=DEFAULT)
    parser.add_argument("--file", type=Path)
    args = parser.parse_args()
    chapter = args.exercise.split("/")[0]
    solution = args.file or REPO / "exercises" / chapter / "solutions" / (
        args.exercise.split("/")[1].replace("-", "_") + ".py"
    )
    env = environment()
    slam = str(BIN / "slamcourse")
    commands = {
        "python -c 'import numpy, hypothesis' (baseline)": [
            sys.executable,
            "-c",
            "import numpy, hypothesis",
        ],
        f"slamcourse check {args.exercise} --file …": [
            slam,
            "check",
            args.exercise,
            "--file",
            str(solution),
            "--no-record",
        ],
    }
    medians = interleaved(commands, args.runs, env)
    report(
        f"code check, whole process, median of {args.runs} interleaved runs",
        medians,
        "python -c 'import numpy, hypothesis' (baseline)",
        1.5,
    )
    repeated(args.exercise, solution, args.repeats)


def repeated(exercise: str, solution: Path, repeats: int) -> None:
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    engine = Engine.open(Settings.from_env(record=False), with_progress=False)
    engine.start_workers()
    times = []
    try:
        engine.submit_code(exercise, path=solution)  # first check: imports, caches
        for _ in range(repeats):
            time.sleep(0.5)  # the learner edits; the spare worker finishes starting meanwhile
            start = time.perf_counter()
            verdict = engine.submit_code(exercise, path=solution).verdict
            times.append(time.perf_counter() - start)
            assert verdict.passed, verdict.feedback
    finally:
        engine.close()
    times.sort()
    p50 = statistics.median(times)
    p90 = times[int(0.9 * (len(times) - 1))]
    verdict_mark = "ok" if p50 <= 0.150 else "over 150 ms"
    print(
        f"repeated check in a running engine ({repeats} checks, "
        f"{verdict.details['examples']} examples each, isolation {verdict.details['isolation']})"
    )
    print(f"  p50 {p50 * 1000:.1f} ms  p90 {p90 * 1000:.1f} ms  {verdict_mark}")


if __name__ == "__main__":
    main()
