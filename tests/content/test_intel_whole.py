"""``intel/whole-graph``: the learner's whole optimiser on the full INTEL graph, in the sandbox.

The fast tests check the reference figure, the exercise's own sandbox limits, its single
strategy input, and that every mutant is already wrong on the cheap fixed examples (so a wrong
file is rejected in about a second, never after a minute on the whole graph) while every correct
variant is right there. The slow ones grade files through the real sandbox, the whole graph
included.
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


def _right(function: Callable[..., Any], example: dict[str, Any]) -> bool:
    """Whether ``function`` gives the reference's χ² on ``example`` (raising is wrong)."""
    try:
        got = function(**example)
    except Exception:  # e.g. a singular H: graded as 'raised'
        return False
    return _close(got, _ref("intel_chi2")(**example))


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


@pytest.mark.parametrize("path", MUTANTS, ids=lambda p: p.stem)
def test_every_mutant_is_wrong_on_a_cheap_example(path: Path) -> None:
    mutant = _learner_function(path)
    wrong = [ex for ex in SPEC.options.examples if not _right(mutant, ex)]
    assert wrong, f"{path.name} is right on every fixed example"


@pytest.mark.parametrize("path", VARIANTS, ids=lambda p: p.stem)
def test_every_variant_is_right_on_the_cheap_examples(path: Path) -> None:
    variant = _learner_function(path)
    for ex in SPEC.options.examples:
        assert _right(variant, ex), ex["iterations"]


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
    verdict = _grade(FOLDER / "solutions" / "intel_chi2.py")
    assert verdict.status == "passed", verdict.feedback
    assert verdict.details["examples"] == len(SPEC.options.examples) + 1
