"""Generic mistakes that only boundary inputs reveal: the fixture chapter ``boundaries`` declares
its argument types (an angle, a pair of poses, covariances, a g2o text) and ships mutants that
pass every example and drawn input, and fail once the types' boundary inputs are added.

The functions run in-process here, called the way the sandbox calls them (each call on its
own copy of the input, the result as plain data, an argument changed in place reported), so
that this proves the test sets themselves; the validator grades the same files through the
sandbox (tests/engine/test_fixture_course.py).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.model import ExerciseSpec
from slamcourse.grading import testset
from slamcourse.grading.domains import boundary_classes
from slamcourse.kinds.code import submission_files
from tests.callees import in_process, load
from tests.conftest import FIXTURE_COURSE

COURSE = load_course(FIXTURE_COURSE)
EXERCISES = ["boundaries/wrap", "boundaries/pose-distance", "boundaries/add-noise"]
EXERCISES.append("boundaries/read-edges")


def grade(spec: ExerciseSpec, tests: testset.TestSet, path: Path) -> Any:
    opts = spec.options
    outcome, _ = testset.run_cases(
        tests,
        in_process(load(path, opts.function)),
        signature=opts.signature,
        returns=opts.returns,
        tolerance=opts.tolerance,
        mutable=opts.mutates,
    )
    return outcome


def with_and_without_types(spec: ExerciseSpec) -> tuple[testset.TestSet, testset.TestSet]:
    """The exercise's test set, and the one it would have without declared types."""
    bare = dataclasses.replace(spec, options=dataclasses.replace(spec.options, types=()))
    return testset.build(spec), testset.build(bare)


@pytest.mark.parametrize("exercise", EXERCISES)
def test_only_boundary_inputs_reject_the_generic_mutants(exercise: str) -> None:
    spec = COURSE.exercise(exercise)
    full, bare = with_and_without_types(spec)
    assert boundary_classes(spec.options.types) <= set(full.boundary_classes)
    assert not any(c.origin.startswith("boundary") for c in bare.cases)
    mutants, variants = submission_files(spec)
    assert len(mutants) >= 3 and len(variants) >= 3
    for path in mutants:
        assert grade(spec, bare, path).passed, f"{path.name} is caught without boundaries"
        outcome = grade(spec, full, path)
        assert not outcome.passed, f"{path.name} passes the boundary inputs"
        assert outcome.failure.origin.startswith("boundary: "), outcome.failure.origin
    for path in [spec.options.solution, *variants]:
        outcome = grade(spec, full, path)
        assert outcome.passed, (path.name, outcome.failure)


@pytest.mark.parametrize(
    ("exercise", "mutant", "label"),
    [
        ("boundaries/wrap", "atan2.py", "angle ±π (a)"),
        ("boundaries/wrap", "rounded-pi.py", "angle next to ±π (a)"),
        ("boundaries/wrap", "array-in-place.py", "whole numbers as int (a)"),
        ("boundaries/pose-distance", "list-copy.py", "tuple (b)"),
        ("boundaries/pose-distance", "same-pose-shortcut.py", "ndarray (a)"),
        ("boundaries/pose-distance", "copy-of-b.py", "whole numbers as int (b)"),
        ("boundaries/add-noise", "zeros-like.py", "identity (P)"),
        ("boundaries/read-edges", "line-regex.py", "CRLF line ends (text)"),
        ("boundaries/read-edges", "drop-last-line.py", "no final newline (text)"),
        ("boundaries/read-edges", "decimal-regex.py", "exponent notation (text)"),
        ("boundaries/read-edges", "edge-block.py", "edge line first (text)"),
        ("boundaries/read-edges", "first-field.py", "blank lines and trailing spaces (text)"),
    ],
)
def test_each_mistake_fails_on_its_own_class(exercise: str, mutant: str, label: str) -> None:
    spec = COURSE.exercise(exercise)
    tests = testset.build(spec)
    only = dataclasses.replace(
        tests, cases=[c for c in tests.cases if c.origin == f"boundary: {label}"]
    )
    assert only.cases
    path = spec.path.parent / "mutants" / spec.path.stem / mutant
    assert not grade(spec, only, path).passed


def test_a_heading_difference_across_pi_rejects_a_function_that_does_not_wrap() -> None:
    spec = COURSE.exercise("boundaries/pose-distance")
    tests = testset.build(spec)
    across = [c for c in tests.cases if c.origin == "boundary: headings across ±π (a, b)"]
    assert len(across) >= 4
    path = spec.path.parent / "mutants" / "pose-distance" / "no-wrap.py"
    outcome = grade(spec, dataclasses.replace(tests, cases=across), path)
    assert not outcome.passed and len(outcome.failures) == len(across)


def test_an_argument_changed_in_place_is_caught_on_an_array_input() -> None:
    spec = COURSE.exercise("boundaries/add-noise")
    tests = testset.build(spec)
    arrays = [c for c in tests.cases if c.origin == "boundary: ndarray (P)"]
    path = spec.path.parent / "mutants" / "add-noise" / "in-place.py"
    outcome = grade(spec, dataclasses.replace(tests, cases=arrays), path)
    assert not outcome.passed and outcome.failure.kind == "mutated"


def test_a_failure_on_an_ndarray_input_is_reported_as_json() -> None:
    """The verdict's details are JSON (the batch grader writes them, `check --json` prints
    them): the failing input of an `ndarray` boundary class comes back as plain lists, and the
    sentence still says which class it was. Graded through the real sandbox."""
    import json

    from slamcourse.kinds import get_kind

    spec = COURSE.exercise("boundaries/add-noise")
    tests = testset.build(spec)
    arrays = [c for c in tests.cases if c.origin == "boundary: ndarray (P)"]
    path = spec.path.parent / "mutants" / "add-noise" / "in-place.py"
    verdict = get_kind("code").check_source(
        spec,
        path.read_text(encoding="utf-8"),
        path.name,
        tests=dataclasses.replace(tests, cases=arrays),
        shrink=False,
    )
    assert not verdict.passed
    data = json.loads(json.dumps(verdict.details))
    assert isinstance(data["input"]["P"], list) and data["boundary"] == "ndarray (P)"
