"""Naming a misconception in code feedback: only when it explains the learner's function."""

from __future__ import annotations

from slamcourse.course.model import Tolerance
from slamcourse.grading.properties import Failure, Outcome, matching_misconception
from slamcourse.grading.returns import parse_returns

TOL = Tolerance(rtol=1e-6, atol=1e-9)


def landmarks_only(num_landmarks: int) -> int:
    return 2 * num_landmarks


def test_a_special_case_is_not_blamed_on_a_misconception_it_does_not_share() -> None:
    """The learner is right for 5 landmarks but returns 0 for none; "landmarks only" also gives 0
    there, yet it is wrong for 5, where the learner is right: it is not the learner's idea."""
    returns = parse_returns("integer")
    outcome = Outcome(failures=[Failure({"num_landmarks": 0}, 3, 0, "expected 3", "mismatch")])
    candidates = [("landmarks-only", landmarks_only)]
    assert matching_misconception(outcome, returns, TOL, candidates) == "landmarks-only"
    outcome.agreed.append(({"num_landmarks": 5}, 13))  # the learner was right for 5
    assert matching_misconception(outcome, returns, TOL, candidates) is None


def test_a_misconception_that_explains_every_input_is_named() -> None:
    returns = parse_returns("integer")
    outcome = Outcome(
        failures=[
            Failure({"num_landmarks": 1}, 5, 2, "expected 5", "mismatch"),
            Failure({"num_landmarks": 4}, 11, 8, "expected 11", "mismatch"),
        ]
    )
    candidates = [("landmarks-only", landmarks_only)]
    assert matching_misconception(outcome, returns, TOL, candidates) == "landmarks-only"
