"""A call that returns while a process it started still runs stops its batch there.

Every later call would share the CPU with what it left running (a fork bomb's spinning
children made each exercise of such a learner take seconds), so the worker reports the call
with ``stop: "processes"`` and answers no more of the batch; the worker's end kills the rest.
A process that was waited for, or that has exited, is no reason to stop.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from slamcourse.sandbox import LoadResult, Worker

MakeWorker = Callable[..., tuple[Worker, LoadResult]]  # the make_worker fixture (conftest.py)


def test_a_call_that_leaves_spinning_children_stops_the_batch(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import os
        def f(n):
            if n == 2:
                for _ in range(3):
                    if os.fork() == 0:
                        while True:
                            pass
            return n
        """
    )
    assert loaded.ok
    start = time.monotonic()
    results = worker.call_many([[0], [1], [2], [3], [4]])
    assert [r.value for r in results] == [0, 1, 2]
    assert [r.stopped for r in results] == [None, None, "processes"]
    worker.close()
    assert time.monotonic() - start < 5.0


def test_children_waited_for_or_exited_do_not_stop_it(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import os
        def f(n):
            pid = os.fork()
            if pid == 0:
                os._exit(0)
            if n % 2 == 0:
                os.waitpid(pid, 0)  # waited for
            else:
                for _ in range(1000):  # exited, not waited for (the learner's to reap)
                    if os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT):
                        break
                    time.sleep(0.001)
            return n

        import time
        """
    )
    assert loaded.ok
    results = worker.call_many([[n] for n in range(6)])
    assert [r.value for r in results] == list(range(6))
    assert not any(r.stopped for r in results)


def test_the_verdict_says_a_process_was_left_running() -> None:
    """Through the grader: a correct function that leaves a child running on its fifth input
    fails there, at once, and is told why; a wrong one that forks on every input (the fork
    bomb of a hostile learner) is told what was wrong, and is stopped after its first call
    too, long before its children could slow every other call down."""
    from slamcourse.course.loader import load_course
    from slamcourse.kinds import get_kind
    from tests.conftest import FIXTURE_COURSE

    spec = load_course(FIXTURE_COURSE).exercise("basics/range-bearing")
    kind = get_kind("code")
    leaves = (
        "import math, os\ncalls = []\ndef range_bearing(dx, dy, theta):\n"
        "    calls.append(1)\n"
        "    if len(calls) == 5 and os.fork() == 0:\n"
        "        while True:\n            pass\n"
        "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
    )
    verdict = kind.check_source(spec, leaves, "leaves.py")  # type: ignore[attr-defined]
    assert verdict.status == "failed" and verdict.details["left_running"] == 5
    assert "returned while a process it started was still running (test input 5 of" in (
        verdict.feedback
    )
    bomb = (
        "import os\ndef range_bearing(dx, dy, theta):\n    for _ in range(200):\n"
        "        try:\n            if os.fork() == 0:\n                while True:\n"
        "                    pass\n        except OSError:\n            break\n    return 0\n"
    )
    start = time.monotonic()
    verdict = kind.check_source(spec, bomb, "bomb.py")  # type: ignore[attr-defined]
    assert time.monotonic() - start < 3.0
    assert verdict.status == "failed" and verdict.details["left_running"] == 1
