"""The order of `next` (issue 15, item 12) against the fixture course (two chapters: basics, with
eleven exercises, then boundaries, with four): after an answer, the next open exercise after it
in its chapter, then the following chapters, then wrapping; `goto` pins an exercise, solved or
not; skipped exercises are passed over, and named."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from slamcourse.engine import Engine
from slamcourse.settings import Settings
from tests.conftest import FIXTURE_COURSE

BASICS = [
    "basics/distance",
    "basics/heading",
    "basics/count",
    "basics/offset",
    "basics/identity",
    "basics/slope",
    "basics/pick",
    "basics/several",
    "basics/steps",
    "basics/bug",
    "basics/range-bearing",
]
BOUNDARIES = [
    "boundaries/wrap",
    "boundaries/pose-distance",
    "boundaries/add-noise",
    "boundaries/read-edges",
]


@pytest.fixture
def engine(tmp_path: Path) -> Iterator[Engine]:
    settings = Settings(home=tmp_path / "home", workspace=tmp_path / "ws", course=FIXTURE_COURSE)
    with Engine.open(settings) as opened:
        yield opened


def test_after_an_answer_next_is_the_next_open_one_in_the_same_chapter(engine: Engine) -> None:
    assert engine.course.exercise_ids == BASICS + BOUNDARIES  # what these tests assume
    assert engine.next_exercise() == "basics/distance"
    assert engine.submit("basics/bug", "3").passed  # out of order, late in the chapter
    step = engine.next_step()
    assert step.exercise_id == "basics/range-bearing"  # not back to basics/distance
    assert (step.after, step.wrapped, step.passed_over) == ("basics/bug", False, ())
    assert step.note is None
    assert engine.summary()[0]["exercises"][-1]["current"]


def test_after_a_chapter_next_goes_on_to_the_following_chapter(engine: Engine) -> None:
    engine.give_up("basics/range-bearing")
    assert engine.next_exercise() == "boundaries/wrap"


def test_after_the_last_exercise_next_wraps_and_says_so(engine: Engine) -> None:
    engine.give_up("boundaries/read-edges")
    step = engine.next_step()
    assert (step.exercise_id, step.wrapped) == ("basics/distance", True)
    assert step.note is not None and "back to the earliest open one" in step.note


def test_goto_a_solved_exercise_poses_it_and_says_so(engine: Engine) -> None:
    assert engine.submit("basics/bug", "3").passed
    step = engine.goto("basics/bug")
    assert (step.exercise_id, step.pinned, step.status) == ("basics/bug", True, "solved")
    assert step.note is not None and "already solved" in step.note
    assert engine.next_exercise() == "basics/bug"  # what goto said is the truth
    assert engine.submit("basics/bug", "3").passed  # answered again: next goes on from it
    assert engine.next_exercise() == "basics/range-bearing"


def test_goto_an_open_exercise_says_nothing_more(engine: Engine) -> None:
    step = engine.goto("boundaries/wrap")
    assert (step.exercise_id, step.pinned, step.note) == ("boundaries/wrap", True, None)
    assert not engine.submit("basics/bug", "2").passed  # a miss elsewhere does not move it
    assert engine.next_exercise() == "boundaries/wrap"


def test_next_names_the_skipped_exercises_it_passes_over(engine: Engine) -> None:
    assert engine.skip("basics/distance") == "basics/heading"
    assert engine.skipped() == ["basics/distance"]
    assert engine.next_step().passed_over == ()  # nothing passed over after the skip itself
    engine.give_up("boundaries/read-edges")  # the end of the course: wrap, past the skipped one
    step = engine.next_step()
    assert (step.exercise_id, step.wrapped) == ("basics/heading", True)
    assert step.passed_over == ("basics/distance",)
    assert step.note is not None and "Passing over 1 skipped exercise: `basics/distance`" in (
        step.note
    )
    row = engine.summary()[0]["exercises"][0]
    assert (row["status"], row["skipped"]) == ("pending", True)


def test_when_only_skipped_exercises_remain_next_goes_back_to_them(engine: Engine) -> None:
    engine.skip("basics/heading")
    for ex in BASICS + BOUNDARIES:
        if ex != "basics/heading":
            engine.give_up(ex)
    step = engine.next_step()
    assert (step.exercise_id, step.only_skipped, step.passed_over) == ("basics/heading", True, ())
    assert step.note is not None and "Only skipped exercises are left" in step.note
    engine.give_up("basics/heading")
    assert engine.next_step().exercise_id is None


def test_goto_and_reset_clear_the_skip(engine: Engine) -> None:
    engine.skip("basics/distance")
    engine.skip("basics/heading")
    assert engine.skipped() == ["basics/distance", "basics/heading"]
    engine.goto("basics/distance")
    assert engine.skipped() == ["basics/heading"]
    engine.reset("basics/heading")
    assert engine.skipped() == []
    engine.skip("basics/count")
    engine.reset()
    assert engine.skipped() == [] and engine.next_exercise() == "basics/distance"


def test_one_mark_and_one_word_per_state() -> None:
    from slamcourse.engine import STATUS_MARK, STATUS_WORD

    assert set(STATUS_MARK) == set(STATUS_WORD) == {"solved", "given_up", "pending", "skipped"}
    assert len(set(STATUS_MARK.values())) == 4
    assert STATUS_MARK["given_up"] not in ("✗", "~")  # ✗ is a wrong answer's mark
