"""CPU and wall time of one complete learner's code exercises: this tree against another revision.

A "learner" is what the batch grader does for one complete submission's code: a new forking
pool (its sandboxed zygote: kept from the learner before, where the tree keeps it), every code
exercise of the bundled course checked with the course's own solution against the batch's test
set (built once, before the rounds), the pool closed. Each round runs in a process of its
own, alternately with this tree's ``src`` and with ``--base``'s (a temporary checkout of that
revision; the course itself is always this tree's, so only the engine differs), and is
accounted for whole: the grader, its zygote, bubblewrap, the workers and the kernel's work for
them, read from a ``cpuacct`` cgroup (cgroup v1) or the ``cpu.stat`` of a cgroup v2 the process
may create. Without either, the machine's busy time from ``/proc/stat`` is used instead
(noisier: it counts everything running) and the report says so.

    python benchmarks/grading_cpu.py [--base HEAD~1] [--rounds 6] [--pairs 2]

Prints each tree's median CPU-seconds and wall seconds per learner and the ratio this / base.
Nothing is asserted: the figures are for notes and issues, measured in one run.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import REPO, Meter, environment


def inner(rounds: int) -> None:
    """One tree's rounds (run with its ``src`` first on the path); prints one line per round."""
    meter = Meter()
    from slamcourse.course.loader import load_course
    from slamcourse.grading import testset
    from slamcourse.grading.pool import WorkerPool
    from slamcourse.kinds import get_kind

    course = load_course(REPO)
    kind = get_kind("code")
    items = []
    for ex in course.exercise_ids:
        spec = course.exercise(ex)
        if spec.kind == "code":
            tests = testset.build(spec, hidden_seeds=[testset.hidden_seed("bench", ex, 0)])
            items.append((spec, tests, Path(spec.options.solution).read_text()))
    import gc
    import inspect

    # as the batch grader's pools: the zygote kept from one learner to the next, where the
    # tree can (from the first round on, which is not reported)
    reuse = {"reuse": True} if "reuse" in inspect.signature(WorkerPool).parameters else {}
    gc.collect()
    gc.freeze()  # as a grading process does before each submission
    print(f"meter {meter.kind}", flush=True)
    if meter.path is not None:
        print(f"cgroup {meter.path}", flush=True)
    for _ in range(rounds + 1):  # the first round warms caches: not reported
        time.sleep(0.3)  # let the previous round's zygote finish exiting
        used, start = meter.read(), time.perf_counter()
        pool = WorkerPool(fork=True, **reuse)
        for spec, tests, source in items:
            verdict = kind.check_source(
                spec, source, "solution.py", tests=tests, shrink=False, spawn=pool.take
            )
            if not verdict.passed:
                raise SystemExit(f"{spec.id}: the course's solution failed: {verdict.feedback}")
        pool.close()
        print(f"round {time.perf_counter() - start:.4f} {meter.read() - used:.4f}", flush=True)


def run_tree(src: Path, rounds: int) -> tuple[str, list[tuple[float, float]]]:
    env = environment()
    env["PYTHONPATH"] = str(src)
    done = subprocess.run(
        [sys.executable, __file__, "--inner", str(rounds)],
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0:
        raise SystemExit(f"rounds with {src} failed:\n{done.stderr[-2000:]}{done.stdout[-500:]}")
    lines = done.stdout.splitlines()
    for line in lines:  # the round process has exited: its cgroup is empty and can go
        if line.startswith("cgroup "):
            Path(line[7:]).rmdir()
    meter = next(line[6:] for line in lines if line.startswith("meter "))
    rows = [tuple(map(float, line.split()[1:3])) for line in lines if line.startswith("round ")]
    return meter, [(wall, cpu) for wall, cpu in rows[1:]]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", default="HEAD~1", help="the revision to compare with")
    parser.add_argument("--rounds", type=int, default=6, help="rounds per tree and pair")
    parser.add_argument("--pairs", type=int, default=2, help="alternations of the two trees")
    parser.add_argument("--inner", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.inner is not None:
        inner(args.inner)
        return
    base = Path(tempfile.mkdtemp(prefix="slambench-base-"))
    try:
        archive = subprocess.run(
            ["git", "-C", str(REPO), "archive", args.base, "src"],
            capture_output=True,
            check=True,
        ).stdout
        subprocess.run(["tar", "-x", "-C", str(base)], input=archive, check=True)
        trees = {"this tree": REPO / "src", f"base {args.base}": base / "src"}
        samples: dict[str, list[tuple[float, float]]] = {name: [] for name in trees}
        meter = ""
        for _ in range(args.pairs):
            for name, src in trees.items():
                meter, rows = run_tree(src, args.rounds)
                samples[name] += rows
    finally:
        shutil.rmtree(base, ignore_errors=True)
    print(f"one complete learner's code exercises, {args.rounds} rounds x {args.pairs} pairs per")
    print(f"tree (CPU from {meter}; medians):")
    medians = {}
    for name, rows in samples.items():
        wall = statistics.median(w for w, _ in rows)
        cpu = statistics.median(c for _, c in rows)
        medians[name] = (wall, cpu)
        print(f"  {name:<22} CPU {cpu:6.2f} s   wall {wall:6.2f} s")
    (this_wall, this_cpu), (base_wall, base_cpu) = medians.values()
    ratios = f"CPU {this_cpu / base_cpu:5.2f}x   wall {this_wall / base_wall:5.2f}x"
    print(f"  {'this / base':<22} {ratios}")


if __name__ == "__main__":
    main()
