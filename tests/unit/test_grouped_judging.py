"""Results judged in groups (``testset.run_cases``, :data:`~slamcourse.grading.testset.GROUP`)
give the outcome judging them one by one gives: the same failures in the same order, the same
inputs counted, the same agreed examples, and a learner stopped at the same result once the
last failure wanted is in."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from slamcourse.course.model import Tolerance
from slamcourse.grading import testset
from slamcourse.grading.testset import Case, run_cases
from slamcourse.sandbox import CallResult

TOL = Tolerance(rtol=1e-6, atol=1e-9)


def worker(answers: dict[int, Any], ran: list[int]) -> Any:
    """A stand-in for ``Worker.call_many``: answers each input ``x`` with ``answers[x]`` (a
    value, or an exception's text), hands each result but the last to the chunk's ``enough``,
    and stops where it says so, as the sandbox does."""

    def call_many(calls: Sequence[Sequence[Any]]) -> list[CallResult]:
        enough = getattr(calls, "enough", None)
        out = []
        for index, (x,) in enumerate(calls):
            ran.append(x)
            got = answers[x]
            result = (
                CallResult("raised", error=got)
                if isinstance(got, str)
                else CallResult("ok", value=got)
            )
            out.append(result)
            if enough is not None and index + 1 < len(calls) and enough(index, result):
                break
        return out

    return call_many


def outcome_of(tests: testset.TestSet, answers: dict[int, Any], group: int, **options: Any) -> Any:
    ran: list[int] = []
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(testset, "GROUP", group)
        outcome, cases = run_cases(
            tests, worker(answers, ran), signature=("x",), returns="array", tolerance=TOL,
            **options,
        )  # fmt: skip
    return (
        [(f.kwargs, f.message, f.kind) for f in outcome.failures],
        outcome.failure.kwargs if outcome.failure else None,
        outcome.examples,
        outcome.agreed,
        sorted(outcome.hidden_failed),
        [c.kwargs if c else None for c in cases],
    ), ran


@given(
    n=st.integers(1, 150),
    wrong=st.sets(st.integers(0, 149), max_size=12),
    raised=st.sets(st.integers(0, 149), max_size=3),
    max_failures=st.sampled_from([1, 2, 5, 100]),
    stop_worker=st.booleans(),
)
def test_groups_judge_as_one_by_one(
    n: int, wrong: set[int], raised: set[int], max_failures: int, stop_worker: bool
) -> None:
    cases = [
        Case({"x": x}, [float(x), 1.0], "example" if x < 3 else "hidden 1" if x > 100 else "drawn")
        for x in range(n)
    ]
    tests = testset.TestSet("demo/pairs", 0, cases)
    answers: dict[int, Any] = {x: [float(x), 1.0] for x in range(n)}
    for x in wrong:
        answers[x] = [float(x), 2.0]
    for x in raised:
        answers[x] = "ValueError: no"
    options = {"max_failures": max_failures, "stop_worker": stop_worker}
    alone, ran_alone = outcome_of(tests, answers, 1, **options)
    grouped, ran_grouped = outcome_of(tests, answers, 16, **options)
    assert grouped == alone
    # the learner ran at most a group further than it would have alone, never past its chunk
    assert ran_grouped[: len(ran_alone)] == ran_alone
    assert len(ran_grouped) - len(ran_alone) < 16


def test_a_stopped_learner_is_read_up_to_its_last_failure_wanted() -> None:
    cases = [Case({"x": x}, [float(x)], "drawn") for x in range(64)]
    answers = {x: [float(x) + (x == 5)] for x in range(64)}
    (failures, _first, examples, *_rest), ran = outcome_of(
        testset.TestSet("demo/one", 0, cases), answers, 16, max_failures=1
    )
    assert [kw for kw, _m, _s in failures] == [{"x": 5}]
    assert examples == 6  # the inputs up to the failure, as if it had stopped there
    assert len(ran) == 16  # it stopped with the group that held the failure


def test_a_call_that_raised_is_judged_at_once() -> None:
    """A learner stopped at its first exception, not a group later (its next call might hang
    until the time limit)."""
    cases = [Case({"x": x}, [float(x)], "drawn") for x in range(64)]
    answers: dict[int, Any] = {x: [float(x)] for x in range(64)}
    answers[5] = "ZeroDivisionError: division by zero"
    (failures, _first, examples, *_rest), ran = outcome_of(
        testset.TestSet("demo/one", 0, cases), answers, 16, max_failures=1
    )
    assert [s for _kw, _m, s in failures] == ["raised"] and examples == 6
    assert len(ran) == 6
