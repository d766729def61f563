"""Every exercise of the real course is itself tested: the validator's checks, one test each
(reference accepted on many variants, misconceptions rejected and recognised, code starters fail
and solutions pass in the real sandbox)."""

from __future__ import annotations

import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.validate import validate_course, validate_exercise

ROOT = bundled_course_root()
COURSE = load_course(ROOT)


def test_course_index_has_no_problems() -> None:
    assert COURSE.problems == []
    assert [c.id for c in COURSE.chapters][:2] == ["state", "observation"]


def test_every_exercise_file_is_placed() -> None:
    unplaced = [
        p
        for p in validate_course(ROOT, variants_per_exercise=0).problems
        if "is not placed" in p.message
    ]
    assert unplaced == []


@pytest.mark.parametrize("exercise_id", COURSE.exercise_ids)
def test_exercise_is_sound(exercise_id: str) -> None:
    problems = validate_exercise(COURSE, exercise_id, 20)
    assert [str(p) for p in problems] == []
