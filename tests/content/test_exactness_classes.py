"""Every class of input the issue "A class graded in minutes, and exact beyond the seed" found
missing is now reached by the generic mechanism, on the real course.

For each class, a shipped mutant of that class (a plausible wrong function) is graded against
the exercise's test set **with its hand-written examples removed**: what rejects it is then the
type-derived boundary inputs (and, where said, the drawn inputs), never an example written for
that exercise. Where ``only_boundary`` is set, the mutant also passes every drawn input: only
the boundary class catches it. The fixture course's ``boundaries`` chapter proves the same for
the text classes without a real-course mutant of their own (an edge line first, blank lines;
tests/engine/test_boundary_mutants.py).

The functions run in-process here (trusted course files), called as the sandbox calls them:
each call on its own copy of the input, an argument changed in place reported.
"""

from __future__ import annotations

import dataclasses
from functools import cache
from pathlib import Path

import pytest

from slamcourse.course.loader import load_course
from slamcourse.grading import testset
from tests.callees import in_process, load

REPO_ROOT = Path(__file__).resolve().parents[2]
COURSE = load_course(REPO_ROOT)

# (the issue's class, exercise, mutant file, boundary class label, only the boundary catches it)
CLASSES = [
    ("whole numbers as Python ints", "motion/odometry-step", "11-int-array.py",
     "whole numbers as int (pose)", True),
    ("an integer identity covariance", "ekf-slam/update-covariance", "12-zeros-like.py",
     "identity (P)", True),
    ("exactly ±π", "se2/wrap-angle", "04-atan2.py", "angle ±π (a)", True),
    ("the floats next to ±π", "se2/wrap-angle", "11-tolerance-at-minus-pi.py",
     "angle next to ±π (a)", True),
    ("headings whose difference crosses ±π, other entries present", "consistency/nees",
     "11-wrapped-estimate-only.py", "headings across ±π (x_true[2], x_hat[2])", False),
    ("angles small but not 0", "drift/heading-drift",
     "11-closed-form-small-rate-shortcut.py", "small nonzero (heading_rate)", False),
    ("tuples where the prompt says sequence", "factor-graphs/fill-in", "12-edges-copy.py",
     "tuple of lists (edges)", True),
    ("large but legal magnitudes (exp(-d²/2) underflows)", "association/chi2-gate",
     "11-exp-overflow.py", "highest value (d2)", True),
    ("large but legal innovations", "jcbb/joint-compatible", "11-exp-overflow.py",
     "entries at range ends (nu)", True),
    ("g2o text without a final newline", "intel/read-edges", "11-drops-last-line.py",
     "no final newline (text)", True),
    ("g2o text in exponent notation", "intel/read-edges", "13-regex-without-exponent.py",
     "exponent notation (text)", True),
    ("g2o text with CRLF line ends", "intel/read-edges", "12-crlf-regex-anchor.py",
     "CRLF line ends (text)", False),
    ("iteration counts too small to converge", "pose-graph/gauss-newton",
     "15-result-inside-loop.py", "lowest value (iterations)", True),
    ("near-ties that are exact ties", "association/nearest-neighbour-fix",
     "04-less-or-equal.py", "exact ties (landmarks)", True),
    ("arguments modified in place", "graph/solve-information", "10-eliminates-in-place.py",
     "ndarray (omega)", True),
    ("state_size in numpy int32 (30,000 landmarks overflow n²)", "state/state-size",
     "int32_size.py", "highest value (num_landmarks)", True),
]  # fmt: skip


@cache
def without_examples(exercise: str) -> testset.TestSet:
    spec = COURSE.exercise(exercise)
    bare = dataclasses.replace(spec, options=dataclasses.replace(spec.options, examples=()))
    return testset.build(bare)


def failing_origins(exercise: str, path: Path) -> set[str]:
    spec = COURSE.exercise(exercise)
    opts = spec.options
    call_many = in_process(load(path, opts.function))
    tests = without_examples(exercise)
    failed = set()
    for case in tests.cases:
        outcome, _ = testset.run_cases(
            tests,
            call_many,
            signature=opts.signature,
            returns=opts.returns,
            tolerance=opts.tolerance,
            mutable=opts.mutates,
            cases=[case],
        )
        if not outcome.passed:
            failed.add(case.origin)
    return failed


@pytest.mark.parametrize(("what", "exercise", "mutant", "label", "only_boundary"), CLASSES)
def test_a_mutant_of_the_class_is_rejected_by_its_boundary_inputs(
    what: str, exercise: str, mutant: str, label: str, only_boundary: bool
) -> None:
    chapter, name = exercise.split("/")
    path = REPO_ROOT / "exercises" / chapter / "mutants" / name / mutant
    assert path.is_file(), path
    tests = without_examples(exercise)
    assert not any(c.origin == "example" for c in tests.cases)
    assert label in tests.boundary_classes, f"{exercise} never reaches {label!r}"
    failed = failing_origins(exercise, path)
    assert f"boundary: {label}" in failed, f"{what}: {mutant} passes the class {label!r}"
    if only_boundary:
        others = sorted(o for o in failed if not o.startswith("boundary: "))
        assert not others, f"{mutant} also fails on {others}: not a proof of the class"


def test_every_class_of_the_issue_is_listed() -> None:
    """The table above names each class the issue lists (a guard against dropping one)."""
    named = " | ".join(row[0] for row in CLASSES)
    for words in ("ints", "±π", "next to ±π", "crosses ±π", "small but not 0", "tuples",
                  "large", "final newline", "exponent", "CRLF", "iteration", "ties",
                  "in place", "int32"):  # fmt: skip
        assert words in named, words
