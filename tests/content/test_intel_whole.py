"""``intel/whole-graph``: the learner's whole optimiser on the full INTEL graph, in the sandbox.

The fast tests check the reference figure, the exercise's own sandbox limits, its single
strategy input, and that every mutant is already wrong on a cheap fixed input (an explicit
example, or a boundary input derived from one: CRLF, no final newline, exponent notation, …), so
a wrong file is rejected in about a second, never after a minute on the whole graph, while every
correct variant is right on all of them. The slow ones grade files through the real sandbox,
the whole graph included.
"""

from __future__ import annotations

import importlib.util
import math
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from slamcourse.course import reference
from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.kinds import get_kind
from slamcourse.sandbox import Limits
from slamcourse.verdict import Verdict

ROOT = bundled_course_root()
FOLDER = ROOT / "exercises" / "intel"
SPEC = load_course(ROOT).exercise("intel/whole-graph")
INTEL_CHI2_AFTER_10 = 215.8302  # measured with the sparse reference; see the first test
RTOL = 1e-4


def _ref(name: str) -> Callable[..., Any]:
    return reference.function(SPEC, name, SPEC.line)


def _learner_function(path: Path) -> Callable[..., Any]:
    """The file's ``intel_chi2``, imported in this process (trusted course files only)."""
    spec = importlib.util.spec_from_file_location(f"whole_{path.stem.replace('-', '_')}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.intel_chi2  # type: ignore[no-any-return]


def _close(got: Any, want: float) -> bool:
    return isinstance(got, int | float) and math.isfinite(got) and abs(got - want) <= RTOL * want


def _right(function: Callable[..., Any], example: dict[str, Any], want: float) -> bool:
    """Whether ``function`` gives the χ² ``want`` on ``example`` (raising is wrong)."""
    try:
        got = function(**example)
    except Exception:  # e.g. a singular H: graded as 'raised'
        return False
    return _close(got, want)


def _cheap_fixed_inputs() -> list[tuple[dict[str, Any], float]]:
    """The test set's explicit examples and boundary inputs on small graphs (at most 8 poses),
    each with the reference's χ²: what a submission meets before the whole graph."""
    from slamcourse.grading import testset

    tests = testset.build(SPEC)
    return [
        (case.kwargs, case.expected)
        for case in tests.cases
        if case.fixed and case.kwargs["text"].count("VERTEX_SE2") <= 8
    ]


CHEAP = _cheap_fixed_inputs()


def _grade(path: Path) -> Verdict:
    source = path.read_text(encoding="utf-8")
    return get_kind("code").check_source(SPEC, source, path.name)  # type: ignore[attr-defined]


MUTANTS = sorted((FOLDER / "mutants" / "whole-graph").glob("*.py"))
VARIANTS = sorted((FOLDER / "variants" / "whole-graph").glob("*.py"))


def test_the_reference_reproduces_the_intel_chi2() -> None:
    text = (FOLDER / "data" / "input_INTEL.g2o").read_text(encoding="utf-8")
    got = _ref("intel_chi2")(text=text, iterations=10)
    assert got == pytest.approx(INTEL_CHI2_AFTER_10, rel=RTOL)


def test_the_exercise_runs_with_its_own_limits() -> None:
    assert SPEC.options.sandbox_limits() == Limits(
        call_seconds=90, total_seconds=240, cpu_seconds=240
    )
    assert SPEC.options.max_examples == 1


def test_the_strategy_is_exactly_the_whole_graph() -> None:
    from hypothesis import find
    from hypothesis.errors import HypothesisWarning

    with warnings.catch_warnings():  # "overly large repr": the input is the 216 kB file
        warnings.simplefilter("ignore", HypothesisWarning)
        drawn = find(_ref(SPEC.options.strategy or "")(), lambda _: True)
    data = (FOLDER / "data" / "input_INTEL.g2o").read_text(encoding="utf-8")
    assert drawn == {"text": data, "iterations": 10}


def test_the_fixed_examples_are_small() -> None:
    assert all(ex["text"].count("VERTEX_SE2") <= 8 for ex in SPEC.options.examples)


def test_there_are_enough_mutants_and_variants() -> None:
    assert len(MUTANTS) >= 8 and len(VARIANTS) >= 3


def test_the_cheap_inputs_include_every_example_and_boundary_inputs() -> None:
    origins = [case for case, _ in CHEAP]
    assert all(ex in origins for ex in SPEC.options.examples)
    assert len(CHEAP) > len(SPEC.options.examples)


@pytest.mark.parametrize("path", MUTANTS, ids=lambda p: p.stem)
def test_every_mutant_is_wrong_on_a_cheap_input(path: Path) -> None:
    mutant = _learner_function(path)
    wrong = [ex for ex, want in CHEAP if not _right(mutant, ex, want)]
    assert wrong, f"{path.name} is right on every cheap fixed input"


@pytest.mark.parametrize(
    "path", [*VARIANTS, FOLDER / "solutions" / "intel_chi2.py"], ids=lambda p: p.stem
)
def test_every_variant_is_right_on_the_cheap_inputs(path: Path) -> None:
    variant = _learner_function(path)
    for ex, want in CHEAP:
        assert _right(variant, ex, want), ex["iterations"]


def test_the_shipped_solution_solves_sparse() -> None:
    """The solution assembles H as a scipy.sparse matrix and solves it with spsolve, as the
    orderings chapter teaches (a dense 3681 × 3681 solve per step is what it avoids)."""
    source = (FOLDER / "solutions" / "intel_chi2.py").read_text(encoding="utf-8")
    assert "scipy.sparse" in source and "spsolve" in source


@pytest.mark.parametrize(
    ("mutant", "misconception"),
    [("01-no-angle-wrap.py", "no-angle-wrap"), ("02-jacobian-sign.py", "jacobian-sign")],
)
def test_the_two_classic_mistakes_are_named(mutant: str, misconception: str) -> None:
    verdict = _grade(FOLDER / "mutants" / "whole-graph" / mutant)
    assert verdict.status == "failed", verdict.feedback
    assert verdict.misconception == misconception, verdict.feedback
    assert "fixed edge cases" in verdict.feedback


@pytest.mark.slow
def test_the_solution_passes_as_a_learner_submission_on_the_whole_graph() -> None:
    from slamcourse.grading import testset

    verdict = _grade(FOLDER / "solutions" / "intel_chi2.py")
    assert verdict.status == "passed", verdict.feedback
    assert verdict.details["examples"] == len(testset.build(SPEC).visible)
