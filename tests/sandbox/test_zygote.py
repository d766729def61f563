"""Batched calls, the argument check and the zygote: what the batch grader's sandbox adds.

The attacks of ``test_attacks.py`` run against forked workers too (the ``how`` fixture); these
tests cover what only a zygote or a batch of calls can get wrong.
"""

from __future__ import annotations

import textwrap
import time
from collections.abc import Iterator
from typing import Any

import pytest

from slamcourse.grading.pool import WorkerPool
from slamcourse.sandbox import Limits, Zygote
from tests.sandbox.conftest import MakeWorker, require_level


@pytest.fixture(params=["namespaces", "rlimits"])
def zygote(request: pytest.FixtureRequest) -> Zygote:
    require_level(request.param)
    z = Zygote.spawn(force=request.param)
    request.addfinalizer(z.close)
    return z


@pytest.fixture
def ns_zygote(ns_level: str) -> Iterator[Zygote]:
    """Namespaces only: a defence the rlimits fallback does not claim (its workers run as the
    grader's own user)."""
    with Zygote.spawn(force=ns_level) as z:
        yield z


def _result(pending: Any) -> Zygote:
    assert pending is not None
    return pending.result()  # type: ignore[no-any-return]


def load(z: Zygote, source: str, limits: Limits | None = None) -> object:
    worker = z.worker(limits)
    loaded = worker.load(textwrap.dedent(source), "f.py", "f", None)
    assert loaded.ok, loaded
    return worker


def test_call_many_answers_each_call_with_its_own_result(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        def f(x):
            print(x)
            if x == 2:
                raise ValueError("two")
            return (x, x * 1.5)
        """
    )
    assert loaded.ok
    results = worker.call_many([[1], [2], [3]])
    assert [r.status for r in results] == ["ok", "raised", "ok"]
    assert results[0].value == [1, 1.5] and results[2].value == [3, 4.5]
    assert results[1].error == "ValueError: two"
    assert [r.stdout for r in results] == ["1\n", "2\n", "3\n"]  # each call's own output
    assert worker.call([4]).value == [4, 6.0]  # single calls still work afterwards


def test_a_call_that_changes_an_argument_is_reported(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import numpy as np
        def f(a, b, c):
            if isinstance(a, list):
                a.append(0)
            np.asarray(b)[...] *= 2        # an ndarray changed through a view
            return len(c)
        """
    )
    assert loaded.ok
    import numpy as np

    results = worker.call_many(
        [
            [[1.0], np.array([1.0, 2.0]), (1, 2)],
            [(1.0,), np.array([0.0]), "ab"],  # 0 * 2 == 0: unchanged
            [(1.0,), [float("nan")], [float("nan")]],  # NaN stays NaN: unchanged
        ]
    )
    assert [r.mutated for r in results] == [(0, 1), (), ()]
    assert worker.call([[1.0], [1.0], ()], check=False).mutated == ()


@pytest.mark.parametrize("with_array", [False, True], ids=["plain-data", "array-in-request"])
@pytest.mark.parametrize("batched", [True, False], ids=["pickled-batch", "single-calls"])
def test_every_kind_of_in_place_change_is_found(
    make_worker: MakeWorker, with_array: bool, batched: bool
) -> None:
    """A batch's arguments are compared with the pickle each call's arguments were read from,
    a single call's (sent as JSON) with a pickle the worker makes before the call (pickled
    again: same bytes, unchanged; else one by one): both find the same changes by the same rule
    (types exact, floats by value, NaN equal to NaN, -0.0 equal to 0.0), whether or not the
    request holds an array."""
    worker, loaded = make_worker(
        """
        import numpy as np
        def f(how, x, extra):
            if how == "set":
                x[0][1] = 2.5
            elif how == "int":
                x[0][0] = 1                  # 1.0 -> 1: another type
            elif how == "zero":
                x[0][0] = -0.0               # 0.0 -> -0.0: equal, no change
            elif how == "nan":
                x[1] = float("nan")          # NaN -> another NaN: no change
            elif how == "array":
                x[0] = np.array(x[0])        # a row replaced by an equal array
            elif how == "tuple":
                x[2][0].append(9)            # a list inside a tuple
            elif how == "dict":
                x[3]["b"] = x[3].pop("a")    # keys reordered
            elif how == "grow":
                x.append(None)
            elif how == "extra" and isinstance(extra, np.ndarray):
                extra[1] = 7.0               # an array changed in place
            elif how == "same-value" and isinstance(extra, np.ndarray):
                extra[0] = 0.0               # written, but to the value it had
            return 0
        """
    )
    assert loaded.ok
    import numpy as np

    def argument() -> list:
        return [[0.0, 1.5], float("nan"), ([1],), {"a": 1, "b": 2}]

    extra = np.zeros(2) if with_array else "no array"
    hows = ["none", "set", "int", "zero", "nan", "array", "tuple", "dict", "grow", "extra",
            "same-value"]  # fmt: skip
    calls = [[how, argument(), extra] for how in hows]
    results = worker.call_many(calls) if batched else [worker.call(args) for args in calls]
    changed = {how: r.mutated for how, r in zip(hows, results, strict=True)}
    assert changed == {
        "none": (), "set": (1,), "int": (1,), "zero": (), "nan": (), "array": (1,),
        "tuple": (1,), "dict": (1,), "grow": (1,), "extra": (2,) if with_array else (),
        "same-value": (),
    }  # fmt: skip


def test_a_batch_sent_pickled_arrives_exactly_as_one_sent_as_json(
    make_worker: MakeWorker,
) -> None:
    """A batch's argument lists cross pickled (encode_calls); the learner must receive exactly
    what the tagged JSON of a single call gives: types, dtypes, shapes, values, order."""
    import enum

    import numpy as np

    from slamcourse.grading.testset import Calls
    from slamcourse.sandbox.protocol import encode_calls

    worker, loaded = make_worker(
        """
        import numpy as np
        def describe(v):
            if isinstance(v, np.ndarray):
                return ["ndarray", v.dtype.str, list(v.shape), v.flags.writeable, v.tolist()]
            if isinstance(v, (list, tuple)):
                return [type(v).__name__, [describe(x) for x in v]]
            if isinstance(v, dict):
                return ["dict", [[describe(k), describe(x)] for k, x in v.items()]]
            return [type(v).__name__, repr(v)]
        def f(a, b):
            return str([describe(a), describe(b)])
        """
    )
    assert loaded.ok

    class Level(enum.IntEnum):
        HIGH = 3

    cases = [
        [(1, 2.5, "x"), {"k": [1, (2, 3)], (4, 5): None}],
        [np.arange(6, dtype=np.int32).reshape(2, 3), np.linspace(0, 1, 5)[::2]],
        [[np.float64(0.1), np.int64(7), np.bool_(True)], Level.HIGH],
        [np.array([True, False]), [[-0.0, 1e300], [float("inf"), -1.5]]],
        ["text with \n and \ud800", np.zeros((0, 3))],
    ]
    as_json = [worker.call(list(args)).value for args in cases]
    batch = Calls(list(args) for args in cases)
    batch.encoded = encode_calls(batch)
    assert b'"pickled"' in batch.encoded
    pickled = [r.value for r in worker.call_many(batch)]
    assert pickled == as_json
    assert "'<f8', [0, 3]" in as_json[4]  # an empty array keeps its other dimensions
    assert all(r.mutated == () for r in worker.call_many(batch))


@pytest.mark.parametrize("hang", ["while True: pass", "time.sleep(60)", "sum(range(10**12))"])
def test_a_call_that_hangs_after_quick_ones_is_the_one_timed_out(
    make_worker: MakeWorker, hang: str
) -> None:
    """The quick calls before the hang return within one bell interval, so their replies are
    written but never rung for: each still gets its own result, and the timeout is the hanging
    call's (a pure-Python loop, a sleep, and C code that holds the interpreter lock)."""
    worker, loaded = make_worker(
        f"""
        import time
        def f(n):
            if n < 0:
                {hang}
            return 2 * n
        """,
        limits=Limits(call_seconds=1.0),
    )
    assert loaded.ok
    results = worker.call_many([[n] for n in range(40)] + [[-1], [5]])
    assert [r.value for r in results[:40]] == [2 * n for n in range(40)]
    assert len(results) == 41 and results[40].status == "timeout", results[40:]


def test_a_batch_of_quick_calls_wakes_the_grader_a_few_times_not_once_per_call(
    make_worker: MakeWorker, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The worker rings the grader's bell every few milliseconds of a batch, not per reply."""
    import select

    from slamcourse.sandbox import runner

    worker, loaded = make_worker("def f(n):\n    return n + 1\n")
    assert loaded.ok
    waits = []
    real = select.select

    def counting(*args: object) -> object:
        waits.append(args)
        return real(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(runner.select, "select", counting)
    results = worker.call_many([[n] for n in range(1000)])
    assert [r.value for r in results] == list(range(1, 1001))
    assert len(waits) < 200, len(waits)


def test_a_learner_who_closes_the_bell_is_still_answered(make_worker: MakeWorker) -> None:
    """The bell's descriptor is the learner's to find and close: replies are then read every
    few tens of milliseconds instead, and still each call's own."""
    worker, loaded = make_worker(
        """
        import os, sys
        os.close(int([a for a in sys.argv if a.startswith("bell=")][0][5:]))
        def f(n):
            print(n)
            return -n
        """
    )
    assert loaded.ok
    results = worker.call_many([[n] for n in range(30)])
    assert [r.value for r in results] == [-n for n in range(30)]
    assert [r.stdout for r in results] == [f"{n}\n" for n in range(30)]
    assert worker.call([7]).value == -7


def test_a_flooding_call_stops_the_batch(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        def f(n):
            print("x" * n)
            return n
        """
    )
    assert loaded.ok
    start = time.monotonic()
    results = worker.call_many([[10], [3_000_000]] + [[3_000_000]] * 50)
    assert time.monotonic() - start < 5.0
    assert [r.value for r in results] == [10, 3_000_000]  # stopped after the first flood
    assert results[-1].stopped == "flooded" and results[0].stopped is None
    assert results[-1].output_cut


def test_scipy_but_nothing_else_from_site_packages(make_worker: MakeWorker) -> None:
    worker, loaded = make_worker(
        """
        import scipy.sparse, scipy.sparse.linalg
        def f(name):
            try:
                __import__(name)
            except ImportError as exc:
                return type(exc).__name__
            return "imported"
        """
    )
    assert loaded.ok, loaded
    names = ["numpy", "scipy.linalg", "json", "hypothesis", "slamcourse", "pytest", "yaml"]
    values = [r.value for r in worker.call_many([[n] for n in names])]
    assert values == ["imported"] * 3 + ["ModuleNotFoundError"] * 4


def test_forked_workers_are_fresh_processes(zygote: Zygote) -> None:
    source = """
        import os
        STATE = []
        def f():
            STATE.append(1)
            return [os.getpid(), len(STATE)]
        """
    first = load(zygote, source)
    second = load(zygote, source)
    a, b = first.call([]).value, second.call([]).value  # type: ignore[attr-defined]
    assert a[1] == b[1] == 1 and a[0] != b[0]  # no module state shared, two processes
    first.close()  # type: ignore[attr-defined]
    second.close()  # type: ignore[attr-defined]


def test_a_worker_cannot_read_its_sibling(ns_zygote: Zygote) -> None:
    zygote = ns_zygote
    sibling = load(zygote, "import os\ndef f():\n    return os.getpid()\n")
    pid = sibling.call([]).value  # type: ignore[attr-defined]
    spy = load(
        zygote,
        """
        import os
        def f(pid):
            out = []
            for path in (f"/proc/{pid}/mem", f"/proc/{pid}/environ", f"/proc/{os.getppid()}/mem"):
                try:
                    with open(path, "rb") as handle:
                        handle.read(16)
                    out.append("read")
                except OSError as exc:
                    out.append(type(exc).__name__)
            return out
        """,
    )
    result = spy.call([pid])  # type: ignore[attr-defined]
    assert result.ok and "read" not in result.value, result  # not dumpable: no access


def test_limits_are_per_worker(zygote: Zygote) -> None:
    worker = load(
        zygote,
        "import time\ndef f(n):\n    time.sleep(n)\n    return n\n",
        Limits(call_seconds=0.5),
    )
    results = worker.call_many([[0], [2], [0]])  # type: ignore[attr-defined]
    assert [r.status for r in results] == ["ok", "timeout"]
    other = load(zygote, "def f():\n    return 7\n")
    assert other.call([]).value == 7  # type: ignore[attr-defined]


@pytest.mark.parametrize("level", ["namespaces", "rlimits"])
def test_the_pool_replaces_a_zygote_the_learner_killed(
    level: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Without namespaces a learner's code can kill its zygote: the next exercise gets a new
    one. Under namespaces the zygote is the sandbox's init, which no signal from inside the
    sandbox kills: the same zygote forks the next exercise's worker."""
    require_level(level)
    monkeypatch.setenv("SLAMCOURSE_SANDBOX", level)
    pool = WorkerPool(fork=True)
    try:
        worker = pool.take(Limits())
        first = pool._zygotes[True].result()  # type: ignore[union-attr]
        loaded = worker.load(
            "import os, signal\ndef f():\n    os.kill(os.getppid(), signal.SIGKILL)\n", "f.py", "f"
        )
        assert loaded.ok
        worker.call([])
        worker.close()
        time.sleep(0.2)
        again = pool.take(Limits())
        assert again.load("def f():\n    return 1\n", "f.py", "f").ok
        assert again.call([]).value == 1
        now = pool._zygotes[True].result()  # type: ignore[union-attr]
        assert (now is first and first.alive) if level == "namespaces" else now is not first
        again.close()
    finally:
        pool.close()


def test_a_worker_forked_ahead_and_killed_meanwhile_is_replaced() -> None:
    """The batch pool forks the next exercise's worker while one runs; code that kills it
    (same learner, same zygote) must not make the next exercise fail."""
    pool = WorkerPool(fork=True)
    try:
        first = pool.take(Limits())
        assert first.load(
            "import os, signal\n"
            "def f():\n"
            "    killed = 0\n"
            "    for pid in range(2, 200):\n"
            "        if pid != os.getpid() and pid != os.getppid():\n"
            "            try:\n"
            "                os.kill(pid, signal.SIGKILL)\n"
            "                killed += 1\n"
            "            except OSError:\n"
            "                pass\n"
            "    return killed\n",
            "f.py",
            "f",
        ).ok
        time.sleep(0.3)  # let the next worker be forked ahead
        assert first.call([]).value >= 1  # the worker forked ahead, at least
        time.sleep(0.3)  # let the killed worker finish dying: one killed a moment before it is
        # taken still looks fresh (its pipes open), and its exercise crashes (this learner's own)
        first.close()
        second = pool.take(Limits())
        assert second.load("def f():\n    return 2\n", "f.py", "f").ok
        assert second.call([]).value == 2
        second.close()
    finally:
        pool.close()


def test_a_worker_forked_ahead_serves_an_exercise_whose_time_budgets_differ() -> None:
    """The worker forked ahead with one exercise's limits serves the next exercise when only
    the grader's side of their limits differs (its time budgets: the next exercise's apply),
    and is replaced by a worker forked for it when the process's own limits differ."""
    pool = WorkerPool(fork=True)
    source = (
        "import resource, time\n"
        "def f(t):\n"
        "    time.sleep(t)\n"
        "    return resource.getrlimit(resource.RLIMIT_CPU)[0]\n"
    )

    def forked_ahead() -> None:
        pool._forked.result()  # type: ignore[union-attr]

    try:
        first = pool.take(Limits())
        forked_ahead()
        zygote = pool._zygotes[True].result()  # type: ignore[union-attr]
        forks = []
        real_fork = zygote._fork
        zygote._fork = lambda *a: forks.append(a) or real_fork(*a)  # type: ignore[method-assign]
        first.close()
        second = pool.take(Limits(call_seconds=0.5, total_seconds=30))
        forked_ahead()
        assert len(forks) == 1  # the next one ahead: the worker forked ahead serves it
        assert second.limits.call_seconds == 0.5
        assert second.load(source, "f.py", "f").ok
        assert second.call([0]).value == Limits().cpu_seconds
        assert second.call([1.5]).status == "timeout"  # (its own budget, not the default 5 s)
        second.close()
        third = pool.take(Limits(cpu_seconds=7))
        forked_ahead()
        assert len(forks) == 3  # one for it (RLIMIT_CPU), then the next one ahead
        assert third.load(source, "f.py", "f").ok
        assert third.call([0]).value == 7
        third.close()
    finally:
        pool.close()


def test_the_caller_can_stop_a_batch_once_it_has_enough(make_worker: MakeWorker) -> None:
    """The validator needs one failure per file: the worker is stopped mid-batch (a slow
    input later in the batch is never computed), and says it was stopped."""
    from slamcourse.grading.testset import Calls

    worker, loaded = make_worker("import time\ndef f(n):\n    time.sleep(n)\n    return n\n")
    assert loaded.ok
    calls = Calls([[0], [0.01], [3], [3]])
    calls.enough = lambda index, result: index == 1
    start = time.monotonic()
    results = worker.call_many(calls)
    assert time.monotonic() - start < 2.0
    assert [r.value for r in results] == [0, 0.01]
    assert not worker.alive


def test_a_zygote_asked_to_preload_imports_after_its_first_fork() -> None:
    """``preload``: modules the zygote imports once its first worker is forked, so every later
    worker finds them imported (scipy for the optimisers on real data); the first worker is not
    kept waiting for them."""
    source = """
        import sys
        def f():
            return "scipy.sparse.linalg" in sys.modules
        """
    with Zygote.spawn(preload=("scipy.sparse.linalg", "no_such_module_at_all")) as z:
        first, second = load(z, source), load(z, source)
        assert first.call([]).value is False  # type: ignore[attr-defined]
        assert second.call([]).value is True  # type: ignore[attr-defined]
    with Zygote.spawn() as z:
        load(z, source)
        assert load(z, source).call([]).value is False  # type: ignore[attr-defined]


def test_a_preloaded_zygote_leaves_learners_their_memory_headroom() -> None:
    """The modules a zygote preloads take address space a learner never asked for: a worker
    forked after the preload gets ``RLIMIT_AS`` raised by what the preload added (scipy: about
    140 MiB), so its code has the headroom of a worker with numpy alone."""
    source = """
        import resource
        def f():
            return resource.getrlimit(resource.RLIMIT_AS)[0]
        """
    limits = Limits()
    with Zygote.spawn(force="rlimits", preload=("scipy.sparse.linalg",)) as z:
        first, second = load(z, source, limits), load(z, source, limits)
        before = first.call([]).value  # type: ignore[attr-defined]
        after = second.call([]).value  # type: ignore[attr-defined]
    assert before == limits.memory_bytes
    assert limits.memory_bytes + (50 << 20) < after < limits.memory_bytes + (400 << 20)


def test_a_zygote_started_ahead_serves_the_next_pool_only_and_is_preloaded() -> None:
    """A batch starts the next learner's zygote while this one is graded: the next forking
    pool takes it (its first worker finds scipy imported: it preloaded while nobody waited),
    and only that pool: the one after starts its own."""
    from slamcourse.grading import pool as pool_module

    source = """
        import os, sys
        def f():
            return [os.getppid(), "scipy.sparse.linalg" in sys.modules]
        """
    pool_module.start_zygote_ahead(require_isolation=False)
    ahead = pool_module._AHEAD[False, True].result()  # started (and ready) in the background
    first_pool = pool_module.WorkerPool(fork=True)
    second_pool = pool_module.WorkerPool(fork=True)
    try:
        worker = first_pool.take(Limits())
        assert _result(first_pool._zygotes.get(True)) is ahead
        assert worker.load(textwrap.dedent(source), "f.py", "f").ok
        assert worker.call([]).value[1] is True  # preloaded before its first fork
        worker.close()
        other = second_pool.take(Limits())
        assert _result(second_pool._zygotes.get(True)) is not ahead
        other.close()
        assert (False, True) not in pool_module._AHEAD  # taken once, by the first pool
    finally:
        first_pool.close()
        second_pool.close()


def test_closed_workers_cgroups_are_swept_and_removed_by_the_time_the_zygote_closes(
    zygote: Zygote,
) -> None:
    """A closed forked worker is killed at once; its exit is awaited and its cgroups swept
    and removed in the background (the next exercise does not wait for it), and all of that
    is done when the zygote closes."""
    import threading

    from slamcourse.sandbox import runner

    if zygote.isolation.cgroups is None:
        pytest.skip("no delegated cgroups here: a forked worker has none to remove")

    def run_one() -> list:
        worker = load(zygote, "def f(x):\n    return x\n")
        cgroups = worker._res.cgroups  # type: ignore[attr-defined]
        assert cgroups is not None and cgroups.dirs
        assert worker.call([1]).value == 1  # type: ignore[attr-defined]
        worker.close()  # type: ignore[attr-defined]
        return list(cgroups.dirs)

    run_one()  # (starts the background sweeper)
    assert runner._REAPER is not None
    gate = threading.Event()
    runner._REAPER.submit(gate.wait, 10.0)  # the sweeps queue behind this
    dirs = run_one() + run_one()
    assert all(d.exists() for d in dirs)  # closing did not wait for the sweep
    threading.Timer(0.3, gate.set).start()
    zygote.close()
    assert [d for d in dirs if d.exists()] == []


def test_a_zygote_started_ahead_and_never_taken_is_closed_at_exit() -> None:
    """The last submissions of a batch may hand in no code: the zygote started ahead for them
    is closed when the process ends, not left to the interpreter (an unclosed socket)."""
    import subprocess
    import sys

    code = (
        "from slamcourse.grading.pool import start_zygote_ahead\n"
        "start_zygote_ahead(require_isolation=False)\n"
        "import time; time.sleep(1.0)\n"
    )
    done = subprocess.run(
        [sys.executable, "-W", "default", "-c", code], capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 0, done.stderr
    assert "unclosed" not in done.stderr, done.stderr


# -- one zygote for one learner after another --------------------------------------------------

LEAVE_FILES = """
import os
def f():
    with open("/tmp/answers.txt", "w") as out:
        out.write("mine")
    os.makedirs("/tmp/a/b", exist_ok=True)
    with open("/tmp/a/b/c.txt", "w") as out:
        out.write("deep")
    os.chmod("/tmp/a", 0o000)  # unreadable to its creator too
    os.symlink("/usr/bin", "/tmp/link")  # a wipe must not follow it
    return sorted(os.listdir("/tmp"))
"""

LIST_TMP = """
import os
def f():
    return [sorted(os.listdir("/tmp")), os.access("/tmp", os.W_OK), os.path.isdir("/usr/bin")]
"""
LEFT = {"a", "answers.txt", "link"}  # what LEAVE_FILES leaves in /tmp (besides the sandbox's
# own: directories that hold binds of files under the host's /tmp, e.g. a venv there)


def test_a_kept_zygote_serves_the_next_learner_with_nothing_of_the_last(ns_level: str) -> None:
    """A batch grader's pool hands its zygote to the next learner's pool once it is reset:
    the same zygote (no sandbox, interpreter or scipy started again), an empty /tmp, and
    nothing the last learner's files pointed at removed."""
    from slamcourse.grading import pool as pool_module

    first = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)
    second = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)
    try:
        worker = first.take(Limits())
        assert worker.load(textwrap.dedent(LEAVE_FILES), "f.py", "f").ok
        found = set(worker.call([]).value)
        assert found >= LEFT
        zygote = first._zygotes[True].result()  # type: ignore[union-attr]
        worker.close()
        first.close()
        assert pool_module._KEPT.get((True, True)) is zygote and zygote.alive  # reset clean: kept
        other = second.take(Limits())
        assert _result(second._zygotes.get(True)) is zygote
        assert other.load(textwrap.dedent(LIST_TMP), "f.py", "f").ok
        listing, writable, usr = other.call([]).value
        assert set(listing) == found - LEFT and writable and usr
        other.close()
    finally:
        first.close()
        second.close()
        pool_module._close_ahead()  # (the zygote kept after the second learner)
    assert not zygote.alive


@pytest.mark.parametrize(
    "leave",
    [
        "import os, time\n"  # a daemon: out of the worker's process group and session
        "def f():\n"
        "    pid = os.fork()\n"
        "    if pid == 0:\n"
        "        os.setsid()\n"
        "        if os.fork() == 0:\n"
        "            time.sleep(60)\n"
        "        os._exit(0)\n"
        "    os.waitpid(pid, 0)\n"
        "    return 1\n",
        "import os, resource\n"  # the zygote's limits, lowered for the next learner's workers
        "def f():\n"
        "    resource.prlimit(os.getppid(), resource.RLIMIT_NOFILE, (20, 20))\n"
        "    return 1\n",
        "import os\n"  # the zygote reniced: the next learner's workers would inherit it
        "def f():\n"
        "    os.setpriority(os.PRIO_PROCESS, os.getppid(), 15)\n"
        "    return 1\n",
        "import os\n"  # /tmp made unwritable for the next learner
        "def f():\n"
        "    os.chmod('/tmp', 0o500)\n"
        "    return 1\n",
        "import ctypes\n"  # a System V shared memory segment outlives its creator
        "def f():\n"
        "    libc = ctypes.CDLL(None, use_errno=True)\n"
        "    return 1 if libc.shmget(0, 4096, 0o1000 | 0o600) >= 0 else ctypes.get_errno()\n",
    ],
    ids=["daemon", "prlimit", "renice", "tmp-mode", "sysv-shm"],
)
def test_a_zygote_that_keeps_anything_of_a_learner_is_not_reset(
    ns_zygote: Zygote, leave: str, request: pytest.FixtureRequest
) -> None:
    """What one learner's code may leave or change in the sandbox that could reach the next
    learner's workers makes the reset fail (the pool then closes the zygote)."""
    worker = load(ns_zygote, leave)
    assert worker.call([]).value == 1  # type: ignore[attr-defined]
    why = ns_zygote.reset()  # (the worker itself is killed by the reset)
    expected = {
        "daemon": "1 process(es) of the last learner still running",
        "prlimit": "the zygote's RLIMIT_NOFILE changed",
        "renice": "the zygote's nice value changed",
        "tmp-mode": "the zygote's /tmp's mode or owner changed",
        "sysv-shm": "a System V IPC object (shm) was left",
    }[request.node.callspec.id]
    assert why == expected
    worker.close()  # type: ignore[attr-defined]


def test_a_zygote_reset_after_a_clean_learner_is_fit_and_still_forks(ns_zygote: Zygote) -> None:
    worker = load(ns_zygote, "def f(x):\n    return x\n")
    assert worker.call([3]).value == 3  # type: ignore[attr-defined]
    worker.close()  # type: ignore[attr-defined]
    assert ns_zygote.reset() is None
    again = load(ns_zygote, "def f(x):\n    return -x\n")
    assert again.call([3]).value == -3  # type: ignore[attr-defined]
    again.close()  # type: ignore[attr-defined]


def test_a_pool_whose_zygote_cannot_be_reset_gives_the_next_learner_a_new_one(
    ns_level: str,
) -> None:
    from slamcourse.grading import pool as pool_module

    first = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)
    second = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)
    try:
        worker = first.take(Limits())
        source = "import os\ndef f():\n    os.chmod('/tmp', 0o500)\n    return 1\n"
        assert worker.load(source, "f.py", "f").ok and worker.call([]).value == 1
        zygote = first._zygotes[True].result()  # type: ignore[union-attr]
        worker.close()
        first.close()
        assert not zygote.alive and (True, True) not in pool_module._KEPT
        other = second.take(Limits())
        assert _result(second._zygotes.get(True)) is not zygote
        assert other.load(textwrap.dedent(LIST_TMP), "f.py", "f").ok
        assert other.call([]).value[1] is True  # a fresh /tmp, writable again
        other.close()
    finally:
        first.close()
        second.close()
        pool_module._close_ahead()


def test_a_zygote_is_started_ahead_only_once_one_could_not_be_kept(
    ns_level: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A batch process starts no zygote ahead while it keeps its learners' zygotes (one
    started for nothing costs a sandbox, an interpreter, numpy and scipy); once a learner's
    could not be reset, the next learner's is started ahead."""
    from slamcourse.grading import pool as pool_module

    monkeypatch.setattr(pool_module, "_LAST_KEPT", {})
    needed = lambda: pool_module.zygote_needed_ahead(require_isolation=True)  # noqa: E731
    assert not needed()  # the first learner of a process
    for source, kept in (
        ("def f():\n    return 1\n", True),
        ("import os\ndef f():\n    os.chmod('/tmp', 0o500)\n    return 1\n", False),
        ("def f():\n    return 1\n", True),
    ):
        pool = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)
        try:
            worker = pool.take(Limits())
            assert worker.load(source, "f.py", "f").ok and worker.call([]).value == 1
            worker.close()
        finally:
            pool.close()
        assert needed() is not kept
    pool_module._close_ahead()


def test_without_namespaces_a_zygote_is_never_kept() -> None:
    """Without a pid namespace the zygote cannot see every process a learner left."""
    with Zygote.spawn(force="rlimits") as fallback:
        worker = load(fallback, "def f(x):\n    return x\n")
        worker.close()  # type: ignore[attr-defined]
        assert fallback.reset() == (
            "no pid namespace: the processes a learner left cannot all be seen"
        )


DAEMON = """
import os, time
def f():
    pid = os.fork()
    if pid == 0:
        os.setsid()
        if os.fork() == 0:
            time.sleep(60)
        os._exit(0)
    os.waitpid(pid, 0)
    return 1
"""


def test_a_daemon_swept_with_its_worker_leaves_the_zygote_fit(ns_zygote: Zygote) -> None:
    """A learner's daemon (its own session, orphaned to the zygote, the sandbox's init) is
    killed with its worker's cgroups and reaped by the zygote: the next learner may come.
    Without cgroups nothing sweeps it, and the zygote says so."""
    worker = load(ns_zygote, DAEMON)
    assert worker.call([]).value == 1  # type: ignore[attr-defined]
    worker.close()  # type: ignore[attr-defined]
    why = ns_zygote.reset()
    if ns_zygote.isolation.cgroups is not None:
        assert why is None
    else:
        assert why == "1 process(es) of the last learner still running"


def test_closing_a_worker_waits_for_nothing_and_its_daemon_goes_with_the_sweep(
    zygote: Zygote,
) -> None:
    """Closing a forked worker waits for no answer of the zygote (which forks the next worker
    meanwhile): the worker is SIGKILLed by a request the zygote does not answer; a daemon it
    started out of its process group is killed by the background sweep of its cgroups."""
    import threading

    from slamcourse.sandbox import runner

    if zygote.isolation.cgroups is None:
        pytest.skip("no delegated cgroups here: nothing sweeps a daemon")
    worker = load(zygote, DAEMON)
    assert worker.call([]).value == 1  # type: ignore[attr-defined]
    in_sandbox = worker._res.proc.pid  # type: ignore[attr-defined]
    pids = worker._res.cgroups.pids()  # type: ignore[attr-defined]
    own = [pid for pid in pids if _pid_in_sandbox(pid) == in_sandbox]
    daemon = [pid for pid in pids if pid not in own]
    assert len(own) == 1 and len(daemon) == 1
    asked = []
    real_ask = zygote._ask
    zygote._ask = lambda *a, **k: asked.append(a) or real_ask(*a, **k)  # type: ignore[method-assign]
    if runner._REAPER is None:
        runner._REAPER = runner.ThreadPoolExecutor(1, thread_name_prefix="sandbox-reap")
    gate = threading.Event()
    runner._REAPER.submit(gate.wait, 10.0)  # the sweep queues behind this
    try:
        worker.close()  # type: ignore[attr-defined]
        assert asked == []
        assert _dies(own[0])
        assert _running(daemon[0])  # (out of the worker's process group: the sweep's)
    finally:
        gate.set()
        zygote._ask = real_ask  # type: ignore[method-assign]
    assert _dies(daemon[0])


def _pid_in_sandbox(pid: int) -> int | None:
    """``pid``'s number in its innermost pid namespace (``NSpid``), None if it is gone."""
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("NSpid:"):
                    return int(line.split()[-1])
    except OSError:
        pass
    return None


def _dies(pid: int, within: float = 5.0) -> bool:
    deadline = time.monotonic() + within
    while time.monotonic() < deadline and _running(pid):
        time.sleep(0.01)
    return not _running(pid)


def _running(pid: int) -> bool:
    """True while ``pid`` is a live process (a zombie, dead but not yet reaped, is not)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_no_process_of_the_sandbox_can_be_traced_by_a_learner(ns_zygote: Zygote) -> None:
    """The zygote is the sandbox's init: there is no bubblewrap init a learner's code could
    ptrace (and so use to outlive its learner); the zygote and every worker are not
    dumpable."""
    other = load(ns_zygote, "import time\ndef f():\n    time.sleep(30)\n")
    worker = load(
        ns_zygote,
        """
        import ctypes, os
        def f():
            libc = ctypes.CDLL(None, use_errno=True)
            found = []
            for name in os.listdir("/proc"):
                if name.isdigit() and int(name) != os.getpid():
                    found.append(libc.ptrace(16, int(name), 0, 0))  # PTRACE_ATTACH
            return [os.getppid(), found]
        """,
    )
    zygote_pid, attached = worker.call([]).value  # type: ignore[attr-defined]
    assert zygote_pid == 1
    assert len(attached) >= 2 and set(attached) == {-1}, attached  # the zygote, the other
    other.close()  # type: ignore[attr-defined]
    worker.close()  # type: ignore[attr-defined]


def test_builtins_patched_by_learner_code_that_runs_around_a_call_are_restored(
    make_worker: MakeWorker,
) -> None:
    """Learner code runs besides the function itself where the worker pickles an argument the
    call filled with the learner's own objects (for the in-place check) and where it flushes a
    stream the learner replaced; what that code patches in ``builtins`` is undone before the
    worker's own code goes on, so every reply is still the call's own."""
    worker, loaded = make_worker(
        """
        import builtins, sys

        class Sneaky:
            def __reduce__(self):
                builtins.memoryview = lambda data: memoryview(b"{}")
                builtins.type = lambda x: int
                return (int, (0,))

        class Stream:
            def write(self, text):
                return len(text)
            def flush(self):
                builtins.memoryview = lambda data: memoryview(b"{}")

        def f(xs, mode):
            if mode == "fill":
                xs.append(Sneaky())
            elif mode == "stream":
                sys.stdout = Stream()
            return [len(xs), 0.5]
        """
    )
    assert loaded.ok
    results = worker.call_many([[[1, 2], "fill"], [[1], "none"], [[1], "stream"], [[], "none"]])
    assert [r.status for r in results] == ["ok"] * 4, results
    assert [r.value for r in results] == [[3, 0.5], [1, 0.5], [1, 0.5], [0, 0.5]]
    assert results[0].mutated == (0,) and results[1].mutated == ()


# -- two zygotes for one learner: with and without scipy ---------------------------------------

HAS_SCIPY = """
import sys
def f():
    return "scipy.linalg" in sys.modules
"""


def test_uses_scipy_reads_the_name_as_a_word() -> None:
    from slamcourse.grading.pool import uses_scipy

    for source in ("import scipy", "from scipy.sparse import csc_matrix", "x = 1  # scipy"):
        assert uses_scipy(source)
    for source in ("import numpy as np", "my_scipy = 1", "scipyish()", ""):
        assert not uses_scipy(source)


def test_a_reusing_pool_forks_each_worker_from_the_zygote_its_source_needs(
    ns_level: str,
) -> None:
    """A batch learner's code that names scipy runs in a worker whose zygote has imported it;
    other code in one from a zygote that has not (a lighter fork), where importing scipy
    still works. Both zygotes are kept for the next learner. A pool that does not reuse its
    zygotes (one learner's checks) forks every worker from one that has."""
    from slamcourse.grading import pool as pool_module

    reusing = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)
    single = pool_module.WorkerPool(fork=True, require_isolation=True)
    try:
        for pool, scipy in ((reusing, False), (reusing, True), (single, False)):
            pool.take(Limits(), scipy=scipy).close()  # (a zygote preloads after its 1st fork)
        found = []
        for pool, scipy in ((reusing, False), (reusing, True), (reusing, False), (single, False)):
            worker = pool.take(Limits(), scipy=scipy)
            assert worker.load(textwrap.dedent(HAS_SCIPY), "f.py", "f").ok
            found.append(worker.call([]).value)
            worker.close()
        assert found == [False, True, False, True]
        worker = reusing.take(Limits(), scipy=False)
        source = "import scipy.sparse.linalg as s\ndef f():\n    return s.spsolve.__name__\n"
        assert worker.load(source, "f.py", "f").ok
        assert worker.call([]).value == "spsolve"
        worker.close()
        zygotes = {scipy: z.result() for scipy, z in reusing._zygotes.items() if z is not None}
        assert set(zygotes) == {False, True} and zygotes[False] is not zygotes[True]
        reusing.close()
        assert pool_module._KEPT.get((True, False)) is zygotes[False]
        assert pool_module._KEPT.get((True, True)) is zygotes[True]
    finally:
        reusing.close()
        single.close()
        pool_module._close_ahead()


def test_a_pool_told_what_comes_forks_each_worker_ahead_as_the_next_take_needs(
    ns_level: str,
) -> None:
    """A batch submission's pool knows its code exercises' limits and whether each names
    scipy: the first worker is forked at once, each next one with the next exercise's limits
    and from its zygote, and none after the last. A take nobody announced still gets its
    worker; the announced ones before the one a take matches are dropped."""
    from slamcourse.grading import pool as pool_module

    big = Limits(cpu_seconds=240)
    plan = [(None, False), (big, False), (None, True), (None, False)]
    pool = pool_module.WorkerPool(fork=True, reuse=True, require_isolation=True)

    def ahead() -> tuple[bool, Limits] | None:
        if pool._forked is None:
            return None
        found = pool._forked.result()
        assert found is not None
        owner, worker = found
        flavours = {z.result(): scipy for scipy, z in pool._zygotes.items() if z is not None}
        return flavours[owner], worker.limits  # type: ignore[attr-defined]

    try:
        pool.expect(plan)
        assert ahead() == (False, Limits())  # forked before the first take
        seen = []
        for limits, scipy in plan:
            worker = pool.take(limits, scipy=scipy)
            assert worker.limits == (limits or Limits())  # type: ignore[attr-defined]
            worker.close()
            seen.append(ahead())
        assert seen == [(False, big), (True, Limits()), (False, Limits()), None]
        pool.expect(plan)
        pool.take(None, scipy=True).close()  # (the third: the first two are dropped)
        assert ahead() == (False, Limits())
        pool.take(Limits(cpu_seconds=7), scipy=False).close()  # (not announced)
        assert ahead() == (False, Limits())  # (still the fourth)
    finally:
        pool.close()
        pool_module._close_ahead()
