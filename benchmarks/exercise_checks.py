"""What one code exercise's check costs a learner, as a ratio to starting Python with numpy.

For every code exercise of the chapters named (default: the chapters beyond the lesson's
second part, 19 onwards), times ``slamcourse check ID --file <the course's own solution>`` as a
whole process (CLI start, the sandboxed worker, every recorded test input, the comparison)
against ``python -c "import numpy"``, runs interleaved so that load drifts hit both alike, and
prints the medians and their ratio. A check that replays its recording is what a learner's
first check costs on a machine where the course is installed.

    python benchmarks/exercise_checks.py [--runs 3] [CHAPTER ...]
"""

from __future__ import annotations

import argparse
import sys

from _common import BIN, REPO, environment, interleaved

from slamcourse.course.loader import load_course

BEYOND = ("robust", "loop-closure", "marginalisation", "se3", "particles", "victoria-park")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chapters", nargs="*", default=list(BEYOND))
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    course = load_course(REPO)
    env = environment()
    baseline = [sys.executable, "-c", "import numpy"]
    rows = []
    for ex in course.exercise_ids:
        spec = course.exercise(ex)
        if spec.kind != "code" or spec.chapter not in args.chapters:
            continue
        check = [str(BIN / "slamcourse"), "check", ex, "--file", str(spec.options.solution)]
        medians = interleaved({"check": check, "numpy": baseline}, args.runs, env, warmup=1)
        rows.append((ex, medians["check"], medians["check"] / medians["numpy"]))
        print(f"{ex:<44} {medians['check']:7.2f} s  {rows[-1][2]:7.1f}× import numpy", flush=True)
    print(f"{len(rows)} code exercises; baseline: python -c 'import numpy'")


if __name__ == "__main__":
    main()
