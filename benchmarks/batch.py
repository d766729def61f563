"""Batch grading throughput and the cost of one submission.

Generates synthetic submissions against a course (default: the fixture course), each answering
every text exercise (right or wrong) and the code exercise with right, wrong, crashing or (a
few) hanging code, then measures in the same run:

1. throughput of `slamcourse grade` over all of them with `--jobs 2` against `--jobs 1`
   (target ≥ 1.8× on an otherwise idle 2-core machine);
2. the whole-process cost of grading one full (right) submission, as a ratio to
   `python -c pass` (interleaved runs, medians).

    python benchmarks/batch.py [--count 100] [--hanging 2] [--runs 5]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import BIN, REPO, environment, interleaved

from slamcourse.batch.submission import (
    Answer,
    Manifest,
    Submission,
    code_path,
    course_hash,
    learner_id,
    write,
)
from slamcourse.course.loader import load_course
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind
from slamcourse.progress import variant_seed_for

COURSE = REPO / "tests" / "fixtures" / "course"

CODE = {
    "right": "import math\n\ndef {f}(dx, dy, theta):\n"
    "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n",
    "wrong": "import math\n\ndef {f}(dx, dy, theta):\n"
    "    return dx * dx + dy * dy, math.atan2(dy, dx) - theta\n",
    "crash": "def {f}(dx, dy, theta):\n    return [1, 2][5]\n",
    "hang": "def {f}(dx, dy, theta):\n    while True:\n        pass\n",
}


def make_class(root: Path, count: int, hanging: int) -> list[Path]:
    """``count`` submissions: text answers right for even learners, off by 10 % for odd ones;
    code right / wrong / crashing in turn, the first ``hanging`` ones looping forever."""
    course = load_course(COURSE)
    digest = course_hash(COURSE)
    text_ids = [e for e in course.exercise_ids if course.exercise(e).kind in ("number",)]
    code_ids = [e for e in course.exercise_ids if course.exercise(e).kind == "code"]
    paths = []
    for i in range(count):
        seed = 1000 + i
        answers = []
        for ex in text_ids:
            spec = course.exercise(ex)
            v = variant_seed_for(seed, ex) if spec.has_variants else 0
            value = float(get_kind(spec.kind).expected(spec, variant(spec, v)))
            answers.append(Answer(ex, v, text=repr(value if i % 2 == 0 else value * 1.1)))
        files = {}
        style = "hang" if i < hanging else ("right", "wrong", "crash")[i % 3]
        for ex in code_ids:
            files[code_path(ex)] = CODE[style].format(f=course.exercise(ex).options.function)
            answers.append(Answer(ex, 0, file=code_path(ex)))
        manifest = Manifest(learner_id(seed), seed, "0.1.0", "custom", digest, tuple(answers))
        paths.append(
            write(
                Submission(manifest, {k: v.encode() for k, v in files.items()}),
                root / f"s{i:03d}.zip",
            )
        )
    return paths


def grade_time(paths: list[Path], jobs: int, env: dict[str, str]) -> float:
    out = Path(tempfile.mkdtemp(prefix="slambatch-out-"))
    cmd = [str(BIN / "slamcourse"), "--course", str(COURSE), "grade", *map(str, paths),
           "--jobs", str(jobs), "--out", str(out)]  # fmt: skip
    start = time.perf_counter()
    done = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"grade failed ({done.returncode}): {done.stderr.decode()[-2000:]}")
    statuses = [json.loads(p.read_text())["status"] for p in sorted(out.glob("*.json"))]
    assert statuses.count("graded") == len(paths), statuses
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=100, help="at least 7")
    parser.add_argument("--hanging", type=int, default=2)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    env = environment()
    root = Path(tempfile.mkdtemp(prefix="slambatch-"))
    paths = make_class(root, args.count, args.hanging)
    load = os.getloadavg()[0]
    print(f"{len(paths)} submissions ({args.hanging} hanging); load average {load:.2f} "
          f"on {os.cpu_count()} cores")  # fmt: skip

    full = next(p for i, p in enumerate(paths) if i >= args.hanging and i % 6 == 0)  # all right
    one = [str(BIN / "slamcourse"), "--course", str(COURSE), "grade", str(full)]
    medians = interleaved(
        {"python -c pass (baseline)": [sys.executable, "-c", "pass"], "grade one submission": one},
        args.runs,
        env,
        warmup=1,
    )
    base, cost = medians["python -c pass (baseline)"], medians["grade one submission"]
    print("Whole process, one full submission (11 exercises, one of them code + 1 hidden run):")
    print(f"  python -c pass  {base * 1000:8.1f} ms")
    print(f"  grade           {cost * 1000:8.1f} ms  {cost / base:6.1f}× the baseline")

    t1 = grade_time(paths, 1, env)
    t2 = grade_time(paths, 2, env)
    speedup = t1 / t2
    print("Throughput:")
    print(f"  --jobs 1  {t1:7.1f} s  {len(paths) / t1:6.2f} submissions/s")
    print(f"  --jobs 2  {t2:7.1f} s  {len(paths) / t2:6.2f} submissions/s")
    mark = "ok" if speedup >= 1.8 else "under 1.8×"
    print(f"  speed-up {speedup:.2f}×  {mark}; load average now {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
