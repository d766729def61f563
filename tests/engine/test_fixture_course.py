"""The engine against the fixture course: one exercise per kind and outcome."""

from __future__ import annotations

from pathlib import Path

import pytest

from slamcourse.course.loader import load_course
from slamcourse.engine import Engine
from slamcourse.progress import Progress
from slamcourse.validate import validate_course
from tests.conftest import FIXTURE_COURSE


@pytest.fixture
def engine(tmp_path: Path) -> Engine:
    return Engine(load_course(FIXTURE_COURSE), Progress.open(tmp_path / "p.sqlite3"))


def grade(engine: Engine, exercise_id: str, answer: str, seed: int = 0):  # type: ignore[no-untyped-def]
    return engine.check(exercise_id, answer, engine.variant(exercise_id, seed=seed), record=False)


def test_fixture_course_loads_in_chapter_order() -> None:
    course = load_course(FIXTURE_COURSE)
    assert course.problems == []
    assert course.exercise_ids[:3] == ["basics/distance", "basics/heading", "basics/count"]
    assert len(course.exercise_ids) == 11


def test_fixture_course_validates() -> None:
    report = validate_course(
        FIXTURE_COURSE, variants_per_exercise=10, min_mutants=0, min_variants=0
    )
    assert report.problems == []
    assert report.exercises == 11


@pytest.mark.parametrize(
    ("exercise", "answer", "status", "misconception", "words"),
    [
        ("basics/distance", "5", "passed", None, "from 4.95 to 5.05"),
        ("basics/distance", "sqrt(25)", "passed", None, ""),
        ("basics/distance", "25", "failed", "squared", "square root"),
        ("basics/distance", "-5", "failed", None, "sign is wrong"),
        ("basics/distance", "50", "failed", None, "factor of 10^1"),
        ("basics/distance", "five", "invalid", None, ""),
        ("basics/distance", "", "invalid", None, ""),
        ("basics/heading", "pi/4", "passed", None, "modulo 2π"),
        ("basics/heading", "pi/4 - 2*pi", "passed", None, ""),
        ("basics/heading", "0.785", "passed", None, ""),
        ("basics/heading", "45", "failed", None, "degrees"),
        ("basics/count", "9", "passed", None, ""),
        ("basics/count", "6", "failed", "forgot-pose", "pose belongs"),
        ("basics/count", "9.5", "invalid", None, "whole number"),
        ("basics/offset", "[3, -3]", "passed", None, ""),
        ("basics/offset", "3 -3", "passed", None, ""),
        ("basics/offset", "[-3, 3]", "failed", "swapped", "other way round"),
        ("basics/offset", "[3, 3]", "failed", None, "2 (second)"),
        ("basics/offset", "[3]", "failed", None, "Expected 2 entries"),
        ("basics/identity", "[[1, 0], [0, 1]]", "passed", None, ""),
        ("basics/identity", "[1 0; 0 1]", "passed", None, ""),
        ("basics/identity", "[[1, 1], [0, 1]]", "failed", None, "(1, 2)"),
        ("basics/slope", "2*x", "passed", None, ""),
        ("basics/slope", "x + x", "passed", None, ""),
        ("basics/slope", "2x", "passed", None, ""),
        ("basics/slope", "x", "failed", "forgot-factor", "exponent"),
        ("basics/slope", "-2*x", "failed", None, "wrong sign"),
        ("basics/slope", "x^3", "failed", None, "your formula gives"),
        ("basics/slope", "2*y", "invalid", None, "y"),
        ("basics/slope", "__import__('os')", "invalid", None, ""),
        ("basics/pick", "a", "passed", None, "all poses"),
        ("basics/pick", "B", "failed", None, "sensor"),
        ("basics/pick", "z", "invalid", None, "no option 'z'"),
        ("basics/pick", "a b", "invalid", None, "exactly one"),
        ("basics/several", "a c", "passed", None, ""),
        ("basics/several", "c,a", "passed", None, ""),
        ("basics/steps", "p m u", "passed", None, ""),
        ("basics/steps", "p m", "invalid", None, "missing u"),
        ("basics/bug", "3", "passed", None, ""),
        ("basics/bug", "2", "failed", None, "sum of squares"),
        ("basics/bug", "1", "failed", None, "does what it should"),
        ("basics/bug", "7", "invalid", None, "lines 1 to 3"),
    ],
)
def test_outcomes(
    engine: Engine, exercise: str, answer: str, status: str, misconception: str | None, words: str
) -> None:
    verdict = grade(engine, exercise, answer)
    assert verdict.status == status, verdict.feedback
    assert verdict.misconception == misconception
    assert words in verdict.feedback


def test_partial_credit(engine: Engine) -> None:
    half = grade(engine, "basics/several", "a")
    assert (half.status, half.score) == ("failed", 0.5)
    assert "missing" in half.feedback
    assert grade(engine, "basics/several", "a b c").score == 0.5
    order = grade(engine, "basics/steps", "u p m")
    assert order.status == "failed" and order.score == pytest.approx(2 / 3)
    assert "only update after measuring" in order.feedback
    assert grade(engine, "basics/offset", "[3, 3]").score == 0.5


def test_variants_are_deterministic_and_distinct(engine: Engine) -> None:
    canonical = engine.variant("basics/distance", canonical=True)
    assert canonical.params == {"dx": 3, "dy": 4}
    v7 = engine.variant("basics/distance", seed=7)
    assert v7 == engine.variant("basics/distance", seed=7)
    assert v7.params != engine.variant("basics/distance", seed=8).params
    want = (v7.params["dx"] ** 2 + v7.params["dy"] ** 2) ** 0.5
    assert engine.check("basics/distance", repr(want), v7, record=False).passed
    mine = engine.variant("basics/distance")
    assert mine.seed >= 1  # each learner gets their own variant


def test_learner_flow(engine: Engine) -> None:
    assert engine.next_exercise() == "basics/distance"
    variant = engine.variant("basics/distance")
    assert not engine.check("basics/distance", "1e9", variant).passed
    assert engine.state("basics/distance").attempts == 1
    engine.check("basics/distance", "nonsense", variant)
    assert engine.state("basics/distance").attempts == 1  # invalid answers cost nothing
    hint = engine.hint("basics/distance", variant)
    assert (hint.number, hint.total, hint.text) == (1, 2, "Pythagoras.")
    assert engine.hint("basics/distance", variant).number == 2
    assert engine.hint("basics/distance", variant).text is None
    answer = repr(float(engine.explanation("basics/distance", variant).split()[3]))
    assert engine.check("basics/distance", answer, variant).passed
    assert engine.next_exercise() == "basics/heading"
    assert engine.skip("basics/heading") == "basics/count"
    assert engine.next_exercise() == "basics/count"
    engine.give_up("basics/count")
    assert engine.next_exercise() == "basics/offset"
    engine.goto("basics/heading")
    assert engine.next_exercise() == "basics/heading"
    engine.reset("basics/distance")
    assert engine.state("basics/distance").status == "pending"


def test_prompt_and_context(engine: Engine) -> None:
    prompt = engine.prompt("basics/distance", engine.variant("basics/distance", canonical=True))
    assert "(3, 4)" in prompt.markdown and prompt.position == (1, 11)
    assert "within 1%" in prompt.how_to_answer
    assert "fixture chapter" in engine.context("basics/distance")
    assert "Angles are in radians" in engine.context("basics/heading")
    bug = engine.prompt("basics/bug", engine.variant("basics/bug"))
    assert "3 │     return s" in bug.markdown
