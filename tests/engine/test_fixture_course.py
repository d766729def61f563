"""The engine against the fixture course: one exercise per kind and outcome."""

from __future__ import annotations

from pathlib import Path

import pytest

from slamcourse.course.loader import load_course
from slamcourse.engine import Engine, Locked
from slamcourse.settings import Settings
from slamcourse.validate import validate_course
from tests.conftest import FIXTURE_COURSE


def settings(tmp_path: Path, **changes: object) -> Settings:
    return Settings(home=tmp_path / "home", workspace=tmp_path / "ws", course=FIXTURE_COURSE).but(
        **changes
    )


@pytest.fixture
def engine(tmp_path: Path) -> Engine:
    with Engine.open(settings(tmp_path)) as opened:
        yield opened


def grade(engine: Engine, exercise_id: str, answer: str, seed: int = 0):  # type: ignore[no-untyped-def]
    return engine.submit(exercise_id, answer, seed=seed).verdict


def test_fixture_course_loads_in_chapter_order() -> None:
    course = load_course(FIXTURE_COURSE)
    assert course.problems == []
    assert course.exercise_ids[:3] == ["basics/distance", "basics/heading", "basics/count"]
    assert len(course.exercise_ids) == 15


def test_fixture_course_validates() -> None:
    report = validate_course(
        FIXTURE_COURSE, variants_per_exercise=10, min_mutants=0, min_variants=0
    )
    assert report.problems == []
    assert report.exercises == 15


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
        ("basics/offset", "[3]", "invalid", None, "expected 2 entries"),
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
        # variant 0 shows the options shuffled and relabelled: pick c) is the pose graph
        # optimiser (authored as a); several shows b) A, a) B, c) E
        ("basics/pick", "c", "passed", None, "all poses"),
        ("basics/pick", "B", "failed", None, "sensor"),
        ("basics/pick", "z", "invalid", None, "no option 'z'"),
        ("basics/pick", "a b", "invalid", None, "exactly one"),
        ("basics/several", "b c", "passed", None, ""),
        ("basics/several", "c,b", "passed", None, ""),
        ("basics/several", "a b", "failed", None, "a) does not apply. B is a consonant."),
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
    half = grade(engine, "basics/several", "b")
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
    assert engine.submit("basics/distance", repr(want), seed=7).passed
    mine = engine.variant("basics/distance")
    assert mine.seed >= 1  # each learner gets their own variant


def test_learner_flow(engine: Engine) -> None:
    assert engine.next_exercise() == "basics/distance"
    assert not engine.submit("basics/distance", "1e9").passed
    assert engine.state("basics/distance").attempts == 1
    unreadable = engine.submit("basics/distance", "nonsense")
    assert not unreadable.counted
    assert engine.state("basics/distance").attempts == 1  # invalid answers cost nothing
    hint = engine.hint("basics/distance")
    assert (hint.number, hint.total, hint.text) == (1, 2, "Pythagoras.")
    assert engine.hint("basics/distance").number == 2
    assert engine.hint("basics/distance").text is None
    params = engine.variant("basics/distance").params
    answer = repr((params["dx"] ** 2 + params["dy"] ** 2) ** 0.5)
    solved = engine.submit("basics/distance", answer)
    assert solved.passed and solved.exercise_status == "solved"
    assert solved.explanation and solved.explanation == engine.explanation("basics/distance")
    assert engine.next_exercise() == "basics/heading"
    assert engine.skip("basics/heading") == "basics/count"
    assert engine.next_exercise() == "basics/count"
    assert engine.give_up("basics/count")  # the explanation
    assert engine.state("basics/count").status == "given_up"
    assert engine.next_exercise() == "basics/offset"
    engine.goto("basics/heading")
    assert engine.next_exercise() == "basics/heading"
    engine.reset("basics/distance")
    assert engine.state("basics/distance").status == "pending"


def test_explanation_is_locked_until_solved_or_given_up(engine: Engine) -> None:
    with pytest.raises(Locked):
        engine.explanation("basics/distance")
    wrong = engine.submit("basics/distance", "1e9")
    assert wrong.explanation is None and wrong.to_dict()["explanation"] is None
    with pytest.raises(Locked):
        engine.explanation("basics/distance")
    assert engine.give_up("basics/distance")
    assert engine.explanation("basics/distance")


def test_hint_nudge_after_repeated_misses_without_a_hint(engine: Engine) -> None:
    assert engine.submit("basics/distance", "1e9").nudge is None
    assert engine.submit("basics/distance", "nonsense").nudge is None  # not counted
    assert engine.submit("basics/distance", "2e9").nudge == "Stuck? A hint is available."
    engine.hint("basics/distance")
    assert engine.submit("basics/distance", "3e9").nudge is None


def test_canonical_answers_are_practice_never_a_solve(engine: Engine) -> None:
    canonical = engine.submit("basics/distance", "5", canonical=True)
    assert canonical.passed and canonical.practice and not canonical.counted
    assert canonical.explanation is not None  # the canonical explanation, for practice
    state = engine.state("basics/distance")
    assert (state.status, state.attempts) == ("pending", 0)
    wrong = engine.submit("basics/distance", "6", canonical=True)
    assert not wrong.counted and engine.state("basics/distance").attempts == 0
    logged = engine.progress.attempts("basics/distance") if engine.progress else []
    assert [a.variant for a in logged] == [0, 0]  # graded and logged
    # an exercise without variants has only the canonical one: that is the learner's own
    own = engine.submit("basics/pick", "c", canonical=True)
    assert own.passed and not own.practice and engine.state("basics/pick").status == "solved"


def test_no_record_grades_without_writing(tmp_path: Path) -> None:
    with Engine.open(settings(tmp_path, record=False)) as engine:
        result = engine.submit("basics/distance", "1e9")
        assert not result.passed and not result.counted
        assert engine.state("basics/distance").attempts == 0


def test_prompt_and_context(engine: Engine) -> None:
    prompt = engine.pose("basics/distance", canonical=True)
    assert "(3, 4)" in prompt.text and prompt.position == (1, 11)
    assert prompt.practice and prompt.variant.seed == 0
    assert "within 1%" in prompt.how_to_answer
    assert prompt.form == {"type": "number", "units": "m", "integer": False, "angle": False}
    assert "fixture chapter" in engine.context("basics/distance")
    assert "Angles are in radians" in engine.context("basics/heading")
    bug = engine.pose("basics/bug")
    assert bug.form["type"] == "line" and bug.form["lines"][2] == "    return s"
    data = engine.pose("basics/offset").to_dict()
    assert data["form"]["type"] == "vector" and data["form"]["length"] == 2
    assert data["hints"] == {"shown": [], "total": len(engine.exercise("basics/offset").hints)}
    pick = engine.pose("basics/pick").to_dict()["form"]
    assert pick["type"] == "choice" and {o["id"] for o in pick["options"]} >= {"a", "b"}
    steps = engine.pose("basics/steps").to_dict()["form"]
    assert steps["type"] == "order" and len(steps["items"]) == 3


def test_chapters_and_segments(engine: Engine) -> None:
    chapter, boundaries = engine.chapters()
    assert chapter.id == "basics" and chapter.exercise_ids[0] == "basics/distance"
    assert boundaries.id == "boundaries" and boundaries.exercise_ids[0] == "boundaries/wrap"
    segments = engine.chapter_segments("basics")
    assert [s.exercise_id for s in segments][:2] == ["basics/distance", "basics/heading"]
    assert segments[-1].exercise_id is None


def test_text_answer_to_code_exercise_is_a_usage_error(engine: Engine) -> None:
    from slamcourse.errors import UsageError

    with pytest.raises(UsageError, match="code exercise"):
        engine.submit("basics/range-bearing", "1")
    with pytest.raises(UsageError, match="answer it with text"):
        engine.submit_code("basics/distance", source="x = 1")
