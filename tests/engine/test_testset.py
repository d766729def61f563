"""Test sets: built once (examples, boundaries, drawn, hidden; each input once, with its
reference output), graded in one pass that stops at a fatal call, a flood or a mutation."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from slamcourse.course.loader import load_course
from slamcourse.grading import testset
from slamcourse.grading.properties import exercise_seed
from slamcourse.grading.returns import compare
from slamcourse.sandbox import CallResult
from tests.conftest import FIXTURE_COURSE

SPEC = load_course(FIXTURE_COURSE).exercise("basics/range-bearing")
OPTS = SPEC.options


def right(dx: float, dy: float, theta: float) -> list[float]:
    return [math.hypot(dx, dy), math.atan2(dy, dx) - theta]


def callee(fn: Any, **extra: Any) -> Any:
    calls: list[int] = []

    def call_many(many: Sequence[Sequence[Any]]) -> list[CallResult]:
        calls.append(len(many))
        return [CallResult("ok", value=fn(*args), **extra) for args in many]

    call_many.calls = calls  # type: ignore[attr-defined]
    return call_many


def grade(tests: testset.TestSet, call_many: Any) -> Any:
    return testset.run_cases(
        tests,
        call_many,
        signature=OPTS.signature,
        returns=OPTS.returns,
        tolerance=OPTS.tolerance,
        mutable=OPTS.mutates,
    )[0]


def test_examples_come_first_then_drawn_then_hidden_each_input_once() -> None:
    tests = testset.build(SPEC, hidden_seeds=[7, 8])
    origins = [c.origin for c in tests.cases]
    assert origins[: len(OPTS.examples)] == ["example"] * len(OPTS.examples)
    kinds = [o.split(":")[0].split(" ")[0] for o in origins]
    assert kinds == sorted(kinds, key=["example", "boundary", "drawn", "hidden"].index)
    keys = [testset.input_key(c.kwargs) for c in tests.cases]
    assert len(keys) == len(set(keys))
    assert tests.hidden_runs == 2
    # each case carries the reference's output on it (the same values ``right`` computes, the
    # bearing modulo 2π), hidden ones included
    for case in tests.cases:
        assert compare(OPTS.returns, right(**case.kwargs), case.expected, OPTS.tolerance) is None


def test_the_same_inputs_every_time_and_hidden_ones_are_new() -> None:
    one = testset.build(SPEC, hidden_seeds=[testset.hidden_seed("s", SPEC.id, 0)])
    two = testset.build(SPEC, hidden_seeds=[testset.hidden_seed("s", SPEC.id, 0)])
    assert [c.kwargs for c in one.cases] == [c.kwargs for c in two.cases]
    visible = {testset.input_key(c.kwargs) for c in one.visible}
    hidden = [c for c in one.cases if c.hidden]
    assert hidden and all(testset.input_key(c.kwargs) not in visible for c in hidden)
    assert testset.hidden_seed("s", SPEC.id, 0) != exercise_seed(SPEC.id)
    assert testset.hidden_seed("s", SPEC.id, 0) != testset.hidden_seed("t", SPEC.id, 0)


def test_a_right_function_passes_in_batched_calls() -> None:
    tests = testset.build(SPEC)
    call_many = callee(right)
    outcome = grade(tests, call_many)
    assert outcome.passed and outcome.examples == len(tests.cases)
    assert max(call_many.calls) == testset.CHUNK  # many inputs per request
    assert len(call_many.calls) == -(-len(tests.cases) // testset.CHUNK)


def test_a_wrong_function_fails_at_the_first_failing_case_with_evidence() -> None:
    def squared(dx: float, dy: float, theta: float) -> list[float]:
        return [dx * dx + dy * dy, math.atan2(dy, dx) - theta]

    tests = testset.build(SPEC)
    outcome = grade(tests, callee(squared))
    assert outcome.failure is not None and outcome.failure.kind == "mismatch"
    first = tests.cases.index(outcome.failure_case)
    assert all(math.isclose(squared(**c.kwargs)[0], c.expected[0]) for c in tests.cases[:first])
    assert 1 < len(outcome.failures) <= 20


def test_a_fatal_call_stops_the_pass() -> None:
    tests = testset.build(SPEC)

    def call_many(many: Sequence[Sequence[Any]]) -> list[CallResult]:
        return [CallResult("ok", value=right(*many[0])), CallResult("timeout", error="5 s")]

    outcome = grade(tests, call_many)
    assert outcome.failure is not None and outcome.failure.kind == "timeout"
    assert outcome.examples == 2


def test_a_flood_stops_the_pass() -> None:
    tests = testset.build(SPEC)
    # a call that printed past the per-call cap (``flooded``) ends the pass right after it
    outcome = grade(tests, callee(right, output_cut=True, stopped="flooded"))
    assert outcome.passed and outcome.stopped == ("flooded", 1) and outcome.examples == 1
    assert outcome.output_cut
    # output cut without a flood (the worker's streams were capped) is noted, and grading goes on
    cut = grade(tests, callee(right, output_cut=True))
    assert cut.passed and cut.stopped is None and cut.examples == len(tests.cases)
    assert cut.output_cut


def test_changing_an_argument_in_place_is_a_failure_of_its_own() -> None:
    tests = testset.build(SPEC)
    outcome = grade(tests, callee(right, mutated=(1,)))
    assert outcome.failure is not None and outcome.failure.kind == "mutated"
    assert "`dy`" in outcome.failure.message
    allowed = testset.run_cases(
        tests,
        callee(right, mutated=(1,)),
        signature=OPTS.signature,
        returns=OPTS.returns,
        tolerance=OPTS.tolerance,
        mutable=("dy",),
    )[0]
    assert allowed.passed


def test_shared_tests_are_built_once_and_survive_a_round_trip(tmp_path: Any) -> None:
    shared = testset.SharedTests("secret", 1)
    first = shared.get(SPEC)
    assert shared.get(SPEC) is first
    shared.save(tmp_path / "t.pickle")
    again = testset.SharedTests.load(tmp_path / "t.pickle")
    assert [c.kwargs for c in again.get(SPEC).cases] == [c.kwargs for c in first.cases]


def test_a_set_one_process_wrote_is_read_by_the_others_and_kept_by_its_own(
    tmp_path: Any, monkeypatch: Any
) -> None:
    """A batch's grading process that built a set writes it for the others and keeps it: it
    never reads its own file back; another process reads it once, when it first needs it;
    an unreadable file is built again (with the same seeds: the same set)."""
    built = testset.SharedTests("secret", 1).get(SPEC)
    path = tmp_path / "set-0.pickle"
    testset.SharedTests.write(built, path)
    index = testset.SharedTests("secret", 1, files={SPEC.id: str(path)})
    index.save(tmp_path / "index.pickle")
    assert testset.SharedTests.load(tmp_path / "index.pickle").get(SPEC) is built  # its own
    monkeypatch.setattr(testset, "_WRITTEN", {})  # (another process)
    other = testset.SharedTests.load(tmp_path / "index.pickle")
    assert other.sets == {}
    read = other.get(SPEC)
    assert read is not built and other.get(SPEC) is read
    assert [c.kwargs for c in read.cases] == [c.kwargs for c in built.cases]
    path.write_bytes(b"not a pickle")
    again = testset.SharedTests.load(tmp_path / "index.pickle").get(SPEC)
    assert [repr(c.expected) for c in again.cases] == [repr(c.expected) for c in built.cases]


def test_a_hidden_run_draws_a_quarter_of_max_examples() -> None:
    """Fresh inputs catch code fitted to the visible ones; a quarter of ``max_examples`` (at
    least ten, at most all of them) per hidden run is enough for that, while the visible inputs
    carry the exactness."""
    assert [testset.hidden_count(n) for n in (1, 8, 20, 40, 100, 200)] == [1, 8, 10, 10, 25, 50]
    tests = testset.build(SPEC, hidden_seeds=[testset.hidden_seed("s", SPEC.id, 0)])
    hidden = [c for c in tests.cases if c.hidden]
    want = testset.hidden_count(OPTS.max_examples)
    assert want < OPTS.max_examples and 0 < len(hidden) <= want
    assert testset.hidden_spec(SPEC).options.max_examples == want
    assert SPEC.options.max_examples == OPTS.max_examples  # the exercise itself is unchanged
