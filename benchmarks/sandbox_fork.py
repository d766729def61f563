"""What a fresh worker costs: started (its own interpreter + numpy import) vs forked by a zygote.

For each of ``--runs`` rounds, interleaved: start a worker with ``Worker.spawn``, load a small
function, call it 200 times in one ``call_many`` request, close it; then the same with a worker
forked by one zygote (``Zygote.worker``; the zygote itself is started once, as the batch grader
starts one per submission, and its start-up is reported apart). Also times 200 single
``call``s against one ``call_many`` of 200 (the round trips a batched request saves).

    python benchmarks/sandbox_fork.py [--runs 15]

Ratios are of medians measured in this run; nothing is asserted.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

from slamcourse.sandbox import Limits, Worker, Zygote

SOURCE = "import numpy as np\ndef f(x, y):\n    return float(np.hypot(x, y))\n"
CALLS = [[float(i), 1.5] for i in range(200)]


def one(make: Callable[[], Worker], batched: bool = True) -> float:
    start = time.perf_counter()
    with make() as worker:
        loaded = worker.load(SOURCE, "f.py", "f", ["x", "y"])
        assert loaded.ok, loaded
        many = worker.call_many
        results = many(CALLS) if batched else [worker.call(args) for args in CALLS]
        assert len(results) == len(CALLS) and all(r.ok for r in results)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    args = parser.parse_args()
    limits = Limits()
    starts: list[float] = []
    spawned: list[float] = []
    forked: list[float] = []
    single: list[float] = []
    with Zygote.spawn() as zygote:
        print(
            f"isolation: {zygote.isolation.level}; zygote start-up {zygote.startup_seconds:.3f} s"
        )
        for _ in range(args.runs):
            spawned.append(one(lambda: Worker.spawn(limits=limits)))
            forked.append(one(lambda: zygote.worker(limits)))
            single.append(one(lambda: zygote.worker(limits), batched=False))
    for _ in range(min(5, args.runs)):
        t = time.perf_counter()
        Zygote.spawn().close()
        starts.append(time.perf_counter() - t)
    m_spawn, m_fork, m_single = map(statistics.median, (spawned, forked, single))
    print(f"started worker, load + 200 calls: {m_spawn * 1000:8.1f} ms (median of {args.runs})")
    print(f"forked worker,  load + 200 calls: {m_fork * 1000:8.1f} ms")
    print(f"forked worker,  200 single calls: {m_single * 1000:8.1f} ms")
    print(f"zygote start + stop:              {statistics.median(starts) * 1000:8.1f} ms")
    print(f"forked vs started: {m_spawn / m_fork:.1f}x faster")
    print(f"call_many vs single calls: {m_single / m_fork:.1f}x faster")


if __name__ == "__main__":
    main()
