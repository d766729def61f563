"""Output floods: a submission that prints hundreds of megabytes gets its verdict in seconds.

The worker mutes stdout and stderr past ``Limits.muted_after`` characters (printing costs
nothing after that); output written around the muted streams (``os.write(1, ...)``) is read and
discarded by the parent, which kills the worker past ``Limits.flood_bytes``. Either way the
result says the output was cut.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import pytest

from slamcourse.sandbox import Limits, LoadResult, Worker

MakeWorker = Callable[..., tuple[Worker, LoadResult]]  # the make_worker fixture (conftest.py)


def test_printing_140_mb_in_calls_is_muted(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        def f(i):
            for _ in range(7):
                print("x" * 1_000_000)
            return i
        """
    )
    assert loaded.ok and not loaded.output_cut
    start = time.monotonic()
    results = [worker.call([i]) for i in range(20)]  # 20 calls x 7 MB = 140 MB
    elapsed = time.monotonic() - start
    assert [r.value for r in results] == list(range(20))
    assert all(r.output_cut for r in results)
    assert results[0].stdout.startswith("x" * 1000)
    assert len(results[0].stdout) < Limits().output_bytes + 200
    assert results[-1].stdout == ""  # muted: nothing reaches the pipe any more
    assert elapsed < 3.0, elapsed


def test_printing_300_mb_at_import_is_muted(make_worker: MakeWorker) -> None:
    start = time.monotonic()
    worker, loaded = make_worker(
        """
        import sys
        for _ in range(300):
            sys.stderr.write("e" * 1_000_000)
        def f():
            return 1
        """
    )
    assert loaded.ok and loaded.output_cut
    assert worker.call([]).value == 1
    assert time.monotonic() - start < 5.0


@pytest.mark.parametrize("chunk", [100_000, 20])
def test_a_call_that_prints_forever_is_stopped_within_a_second(
    make_worker: MakeWorker, chunk: int
) -> None:
    """Past eight times the output budget in one call, a muted write raises: the call ends with
    a reply that says why and stops the batch, long before its time limit; ``except
    Exception`` in the learner's loop does not catch it; the next call starts afresh."""
    worker, loaded = make_worker(
        f"""
        def f(n):
            if n:
                return n
            while True:
                try:
                    print("x" * {chunk - 1})
                except Exception:
                    pass
        """
    )
    assert loaded.ok
    start = time.monotonic()
    results = worker.call_many([[0]] + [[1]] * 5)
    assert time.monotonic() - start < 2.5
    assert len(results) == 1 and results[0].status == "raised" and results[0].stopped == "flooded"
    assert results[0].error.startswith("OutputFlood: your function printed more than 8 MiB")
    assert "a loop that does not end" in results[0].error
    assert results[0].frames[-1].text.startswith("print(")
    assert worker.call([2]).value == 2  # (its own call mark: nothing printed, nothing stopped)


def test_writing_around_the_muted_streams_is_stopped(make_worker: MakeWorker) -> None:
    worker, _ = make_worker(
        """
        import os
        def f():
            chunk = b"y" * (1 << 20)
            for _ in range(300):
                os.write(1, chunk)
            return 1
        """
    )
    start = time.monotonic()
    result = worker.call([])
    assert result.status == "crashed" and result.output_cut
    assert "more than 8 MiB of output" in result.error
    assert time.monotonic() - start < 3.0
    assert worker.call([]).status == "crashed"  # the worker is gone


def test_quiet_code_is_not_marked(make_worker: MakeWorker) -> None:
    worker, _ = make_worker("def f():\n    print('hello')\n    return 2\n")
    result = worker.call([])
    assert result.value == 2 and result.stdout == "hello\n" and not result.output_cut


def test_muted_stream_still_behaves_like_a_stream(make_worker: MakeWorker) -> None:
    worker, _ = make_worker(
        """
        import sys
        def f():
            sys.stdout.write("a")
            print("b", file=sys.stderr, flush=True)
            try:
                sys.stdout.write(b"bytes")
            except TypeError:
                pass
            return [sys.stdout.writable(), sys.stdout.encoding.lower()]
        """
    )
    result = worker.call([])
    assert result.value == [True, "utf-8"], result
    assert result.stdout == "a" and result.stderr == "b\n"


def test_verdicts_say_the_output_was_cut() -> None:
    """Through the grader: a correct, chatty submission passes and is told its output was cut;
    one whose single call floods (3 MB) is stopped at once and told to print less; one that
    prints forever is stopped inside its first call, with the line that printed; one that
    writes around the muted streams fails with a message that says why."""
    from slamcourse.course.loader import load_course
    from slamcourse.kinds import get_kind
    from tests.conftest import FIXTURE_COURSE

    spec = load_course(FIXTURE_COURSE).exercise("basics/range-bearing")
    kind = get_kind("code")
    body = "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
    chatty = "import math\ndef range_bearing(dx, dy, theta):\n    print('x' * 20_000)\n" + body
    verdict = kind.check_source(spec, chatty, "chatty.py")  # type: ignore[attr-defined]
    assert verdict.passed and verdict.details["output_cut"] is True  # 2.6 MB in all
    assert "output beyond the first 1 MiB per stream was cut" in verdict.feedback
    flood = "import math\ndef range_bearing(dx, dy, theta):\n    print('x' * 3_000_000)\n" + body
    start = time.monotonic()
    verdict = kind.check_source(spec, flood, "flood.py")  # type: ignore[attr-defined]
    assert time.monotonic() - start < 5.0
    assert verdict.status == "failed" and verdict.details["flooded"] == 1
    assert "more than 1 MiB of output in one call (test input 1 of" in verdict.feedback
    forever = "def range_bearing(dx, dy, theta):\n    while True:\n        print('x' * 99_999)\n"
    start = time.monotonic()
    verdict = kind.check_source(spec, forever, "forever.py")  # type: ignore[attr-defined]
    assert time.monotonic() - start < 3.0  # (its time limit is 5 s a call)
    assert verdict.status == "failed" and verdict.details["output_cut"] is True
    assert "raised OutputFlood: your function printed more than 8 MiB in one call" in (
        verdict.feedback
    )
    assert "`forever.py:3`" in verdict.feedback
    around = (
        "import math, os\ndef range_bearing(dx, dy, theta):\n"
        "    os.write(1, b'y' * 3_000_000)\n" + body
    )
    verdict = kind.check_source(spec, around, "around.py")  # type: ignore[attr-defined]
    assert verdict.status == "failed" and verdict.details["output_cut"] is True
    assert (
        "printed more than 8 MiB of output" in verdict.feedback and "Print less" in verdict.feedback
    )
