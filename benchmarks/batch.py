"""A class graded as an instructor grades it: throughput, cost per submission, grader overhead.

Builds a class against the bundled course as its learners would hand it in
(``benchmarks/_class.py``: complete learners answering every exercise with the course's own
solutions and correct variants, partial learners answering about half with some shipped
mutants, hostile learners whose code floods, hangs, exits, forks or raises), then in one run:

1. grades the whole class with ``slamcourse grade --jobs 1`` and ``--jobs 2`` in turn,
   ``--pairs`` times (the speed-up: the median of the pairs' ratios, each pair measured
   minutes apart, so that a host whose speed drifts during the run moves both of a pair;
   the results of every run must agree), each run's CPU-seconds (all its processes: grader,
   sandboxes, workers; see ``Meter``), and what that CPU allows: two cores cannot do a run's
   CPU-seconds in less than half of them, so ``--jobs 2`` is at most ``2 × t1 / CPU2`` times
   faster than ``--jobs 1`` took;
2. reports, per complete submission: seconds (median), and the grader's overhead: the
   submission's wall time minus the time spent inside the learner's own calls;
3. extrapolates ``--jobs 2`` to 500 complete submissions, two ways: 500 × the median complete
   submission at ``--jobs 1`` ÷ the whole class's speed-up (which scales this class's set-up
   and its last, slowest learners with it, as if 500 learners paid them ten times), and the
   ``--jobs 2`` run's part not spent grading submissions (set-up, test sets, the end's idle
   process: its wall time minus the submissions' seconds ÷ 2) once, plus 500 × the median
   complete submission's seconds in that run ÷ 2 (two are graded at a time);
4. measures, before grading, what two cores of this machine give two processes of pure
   Python work at the time (a virtual machine's cores are seldom two whole cores): the
   speed-up no ``--jobs 2`` run can exceed here, whatever it does.

    python benchmarks/batch.py [--count 50] [--partial 0.1] [--hostile 0.1] [--pairs 3]

Goals (issue "A class graded in minutes"): 500 complete submissions ≤ 10 min on a 2-core
machine, overhead ≤ 1 s per complete submission, ``--jobs 2`` ≥ 1.8× ``--jobs 1``. These are
printed as measured, never asserted: timings belong to benchmarks, not tests.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _class import make_class
from _common import BIN, REPO, Meter, environment


def grade(
    paths: list[Path], jobs: int, env: dict[str, str], meter: Meter
) -> tuple[float, float, Path]:
    """Wall seconds, CPU-seconds and the results folder of one ``slamcourse grade`` run."""
    out = Path(tempfile.mkdtemp(prefix="slambatch-out-"))
    cmd = [str(BIN / "slamcourse"), "grade", *map(str, paths), "--jobs", str(jobs),
           "--out", str(out), "--secret", "benchmark-secret"]  # fmt: skip
    used, start = meter.read(), time.perf_counter()
    done = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    elapsed, cpu = time.perf_counter() - start, meter.read() - used
    if done.returncode != 0:
        raise SystemExit(f"grade failed ({done.returncode}): {done.stderr.decode()[-2000:]}")
    return elapsed, cpu, out


_SPIN = "n = 0\nfor i in range({count}):\n    n += len(str(i)) + (i & 7)\n"


def machine_speedup(count: int = 6_000_000, rounds: int = 3) -> tuple[float, float]:
    """(speed-up, seconds alone) of two processes running the same pure-Python loop at once
    against one alone (median of ``rounds``, alternated): 2.0 on two idle whole cores."""
    cmd = [sys.executable, "-c", _SPIN.format(count=count)]
    alone, ratios = [], []
    for _ in range(rounds):
        start = time.perf_counter()
        subprocess.run(cmd, check=True)
        one = time.perf_counter() - start
        start = time.perf_counter()
        both = [subprocess.Popen(cmd) for _ in range(2)]
        for proc in both:
            proc.wait()
        two = time.perf_counter() - start
        alone.append(one)
        ratios.append(2 * one / two)
    return statistics.median(ratios), statistics.median(alone)


def results(out: Path) -> dict[str, dict]:
    return {p.stem: json.loads(p.read_text()) for p in sorted(out.glob("*.json"))}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=50, help="submissions in the class")
    parser.add_argument("--partial", type=float, default=0.1, help="share of partial learners")
    parser.add_argument("--hostile", type=float, default=0.1, help="share of hostile learners")
    parser.add_argument(
        "--pairs", type=int, default=3, help="--jobs 1 and --jobs 2 runs, in turn (median ratio)"
    )
    args = parser.parse_args()
    if args.pairs < 1:
        parser.error("--pairs must be at least 1")
    env = environment()
    n_partial = round(args.count * args.partial)
    n_hostile = round(args.count * args.hostile)
    kinds = ["complete"] * (args.count - n_partial - n_hostile)
    kinds += ["partial"] * n_partial + ["hostile"] * n_hostile
    root = Path(tempfile.mkdtemp(prefix="slambatch-"))
    started = time.perf_counter()
    paths = make_class(REPO, root / "class", kinds)
    print(f"class: {kinds.count('complete')} complete, {n_partial} partial, {n_hostile} hostile "
          f"submissions (built in {time.perf_counter() - started:.0f} s); load average "
          f"{os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")  # fmt: skip

    machine, spin = machine_speedup()
    print(f"this machine now: two processes of pure Python work finish {machine:.2f}× faster "
          f"than one ({spin:.1f} s alone): no --jobs 2 run here can do better")  # fmt: skip
    meter = Meter()
    runs: list[tuple[float, float, float, float]] = []  # (t1, cpu1, t2, cpu2) of each pair
    seconds: list[float] = []  # each complete submission's seconds, every --jobs 1 run
    learner: list[float] = []
    right: list[bool] = []
    codes: list[dict] = []
    seconds2: list[float] = []  # ... and every --jobs 2 run
    fixed2: list[float] = []
    try:
        for pair in range(args.pairs):
            t1, cpu1, out1 = grade(paths, 1, env, meter)
            t2, cpu2, out2 = grade(paths, 2, env, meter)
            one, two = results(out1), results(out2)
            shutil.rmtree(out1, ignore_errors=True)
            shutil.rmtree(out2, ignore_errors=True)
            for name, data in one.items():
                other = two[name]
                assert data["status"] == other["status"] == "graded", (name, data.get("error"))
                strip = lambda d: [(e["exercise"], e["status"], e["score"]) for e in d["exercises"]]  # noqa: E731
                assert strip(data) == strip(other), f"{name}: --jobs 1 and --jobs 2 disagree"
            runs.append((t1, cpu1, t2, cpu2))
            print(f"pair {pair + 1}: --jobs 1 {t1:6.1f} s ({cpu1:6.1f} CPU-s), "
                  f"--jobs 2 {t2:6.1f} s ({cpu2:6.1f} CPU-s): {t1 / t2:.2f}×")  # fmt: skip
            sys.stdout.flush()
            complete = [d for n, d in one.items() if n.startswith("complete")]
            seconds += [d["seconds"] for d in complete]
            learner += [
                sum(e.get("learner_seconds", 0.0) for e in d["exercises"]) for d in complete
            ]
            right += [d["score"] == d["max_score"] for d in complete]
            codes += [e for d in complete for e in d["exercises"] if e["kind"] == "code"]
            seconds2 += [d["seconds"] for n, d in two.items() if n.startswith("complete")]
            fixed2.append(t2 - sum(d["seconds"] for d in two.values()) / 2)
    finally:
        meter.close()
        shutil.rmtree(root, ignore_errors=True)

    overhead = [s - inner for s, inner in zip(seconds, learner, strict=True)]
    by_exercise: dict[str, list[float]] = {}
    for e in codes:
        by_exercise.setdefault(e["exercise"], []).append(e["seconds"])
    typical = {ex: statistics.median(s) for ex, s in by_exercise.items()}
    slowest = sorted(typical, key=lambda ex: -typical[ex])[:5]
    count = len(right) // len(runs)
    print(f"complete submissions fully right: {sum(right) // len(runs)} of {count}")
    print(f"one complete submission (--jobs 1, medians over {len(runs)} run(s)):")
    print(f"  wall              {statistics.median(seconds):7.2f} s")
    print(f"  in learner code   {statistics.median(learner):7.2f} s")
    print(f"  grader overhead   {statistics.median(overhead):7.2f} s   (goal ≤ 1 s)")
    print("  slowest code exercises (medians): " + ", ".join(
        f"{ex} {typical[ex]:.2f} s" for ex in slowest))  # fmt: skip
    ratios = [t1 / t2 for t1, _, t2, _ in runs]
    speedup = statistics.median(ratios)
    t1 = statistics.median(r[0] for r in runs)
    t2 = statistics.median(r[2] for r in runs)
    print(f"the whole class (medians of {len(runs)} pair(s), --jobs 1 and --jobs 2 in turn):")
    for jobs, t, cpu in ((1, t1, statistics.median(r[1] for r in runs)),
                         (2, t2, statistics.median(r[3] for r in runs))):  # fmt: skip
        print(f"  --jobs {jobs}  {t:7.1f} s  {len(paths) / t:6.2f} submissions/s  "
              f"{cpu:7.1f} CPU-s  {cpu / t:4.2f} cores busy")  # fmt: skip
    print(f"  speed-up  {speedup:.2f}×   (goal ≥ 1.8×; pairs: "
          f"{', '.join(f'{r:.2f}' for r in ratios)})")  # fmt: skip
    allowed = statistics.median(2 * r[0] / r[3] for r in runs)
    busy = statistics.median(r[1] / r[0] for r in runs)
    print(f"  at most   {allowed:.2f}×   on 2 cores for this CPU: --jobs 1 keeps "
          f"{busy:.2f} cores busy itself; CPU from {meter.kind}")  # fmt: skip
    per_complete = statistics.median(seconds) / speedup
    once = statistics.median(fixed2)
    paired = (once + 500 * statistics.median(seconds2) / 2) / 60
    print(f"500 complete submissions at --jobs 2: {paired:.1f} min as {once:.1f} s once + 500 × "
          f"{statistics.median(seconds2):.2f} s ÷ 2 (the --jobs 2 runs' set-up and idle end, their "
          "median complete submission)")  # fmt: skip
    print(f"500 complete submissions at --jobs 2, extrapolated: {500 * per_complete / 60:.1f} min "
          f"(goal ≤ 10 min); load average now {os.getloadavg()[0]:.2f}")  # fmt: skip
    print(f"500 submissions of this class's mix at --jobs 2: {500 * t2 / len(paths) / 60:.1f} min")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
