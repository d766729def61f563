"""The progress summary is kept up to date, not recomputed (issue 15, item 7): the browser asks
for it with every answer. For any sequence of answers, hints, give-ups, resets, `goto`/`skip`
and writes by another process (the terminal while the browser face runs), the kept summary
equals the full recomputation, and the store's in-memory states equal what is on disk."""

from __future__ import annotations

import sqlite3
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from slamcourse.engine import Engine
from slamcourse.kinds import get_kind
from slamcourse.progress import ExerciseState, Progress
from slamcourse.settings import Settings
from slamcourse.verdict import Verdict
from tests.conftest import FIXTURE_COURSE

ANSWERABLE = ["basics/distance", "basics/heading", "basics/count", "basics/offset"]
EXERCISES = [*ANSWERABLE, "basics/pick", "basics/bug", "boundaries/wrap", "boundaries/read-edges"]
VERDICTS = {
    "passed": Verdict("passed", 1.0, "Correct."),
    "failed": Verdict("failed", 0.0, "Not quite."),
    "invalid": Verdict("invalid", 0.0, "expected a number"),
    "error": Verdict("error", 0.0, "The grader failed."),
    "timeout": Verdict("timeout", 0.0, "Out of time."),
}


def open_engine(tmp: Path) -> Engine:
    return Engine.open(Settings(home=tmp / "home", workspace=tmp / "ws", course=FIXTURE_COURSE))


@pytest.fixture
def engine(tmp_path: Path) -> Iterator[Engine]:
    with open_engine(tmp_path) as opened:
        yield opened


def right_answer(engine: Engine, exercise_id: str, *, canonical: bool = False) -> str:
    spec = engine.exercise(exercise_id)
    value = get_kind(spec.kind).expected(spec, engine.variant(exercise_id, canonical=canonical))
    return str(list(value)) if spec.kind == "vector" else repr(value)


def on_disk(engine: Engine) -> dict[str, Any]:
    """The states as another connection reads them from the file."""
    assert engine.progress is not None
    with Progress.open(engine.progress.path) as fresh:
        return fresh.states()


answer_op = st.tuples(
    st.just("answer"),
    st.sampled_from(ANSWERABLE),
    st.sampled_from(["right", "wrong", "unreadable", "canonical-right"]),
)
record_op = st.tuples(
    st.just("record"), st.sampled_from(EXERCISES), st.sampled_from(sorted(VERDICTS)), st.booleans()
)
one_op = st.tuples(
    st.sampled_from(["hint", "giveup", "reset", "goto", "skip"]), st.sampled_from(EXERCISES)
)
external_op = st.tuples(
    st.just("external"),
    st.sampled_from(EXERCISES),
    st.sampled_from(["passed", "failed", "giveup", "reset", "hint"]),
)
plain_op = st.sampled_from([("reset-all",), ("external-reset-all",), ("summary",)])
operations = st.lists(
    st.one_of(answer_op, record_op, one_op, external_op, plain_op), min_size=1, max_size=25
)


def apply(engine: Engine, other: Progress, op: tuple[Any, ...]) -> None:
    store = engine.progress
    assert store is not None
    match op:
        case ("answer", ex, how):
            if how == "right":
                engine.submit(ex, right_answer(engine, ex))
            elif how == "canonical-right":  # practice: logged, never counted
                engine.submit(ex, right_answer(engine, ex, canonical=True), canonical=True)
            else:
                engine.submit(ex, "1e9" if how == "wrong" else "a number?")
        case ("record", ex, status, practice):
            store.record_attempt(ex, 0, "x", VERDICTS[status], practice=practice)
        case ("hint", ex):
            store.reveal_hint(ex)
        case ("giveup", ex):
            engine.give_up(ex)
        case ("reset", ex):
            engine.reset(ex)
        case ("goto", ex):
            engine.goto(ex)
        case ("skip", ex):
            engine.skip(ex)
        case ("reset-all",):
            engine.reset()
        case ("external-reset-all",):
            other.reset()
        case ("external", ex, what):
            if what in VERDICTS:
                other.record_attempt(ex, 0, "from the terminal", VERDICTS[what])
            elif what == "giveup":
                other.give_up(ex)
            elif what == "reset":
                other.reset(ex)
            else:
                other.reveal_hint(ex)
        case ("summary",):
            engine.summary()
        case _:
            raise AssertionError(op)


@settings(
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(ops=operations)
def test_the_kept_summary_equals_the_full_recomputation_after_any_sequence(
    ops: list[tuple[Any, ...]],
) -> None:
    with tempfile.TemporaryDirectory() as tmp, open_engine(Path(tmp)) as engine:
        assert engine.progress is not None
        with Progress.open(engine.progress.path) as other:  # another process's connection
            engine.summary()
            for op in ops:
                apply(engine, other, op)
                kept = engine.summary()
                assert kept == engine.summary_full(), op
                disk = on_disk(engine)
                assert engine.progress.states() == disk, op
                shown = {
                    r["id"]: (r["status"], r["attempts"]) for ch in kept for r in ch["exercises"]
                }
                for ex, (status, attempts) in shown.items():
                    state = disk.get(ex)
                    assert (status, attempts) == (
                        (state.status, state.attempts) if state else ("pending", 0)
                    ), (op, ex)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(ops=st.lists(st.one_of(record_op, one_op, external_op, plain_op), max_size=30))
def test_changes_since_keeps_a_follower_equal_to_the_store(ops: list[tuple[Any, ...]]) -> None:
    """A reader that applies only what changed since its last revision holds every state."""
    with tempfile.TemporaryDirectory() as tmp, open_engine(Path(tmp)) as engine:
        store = engine.progress
        assert store is not None
        with Progress.open(store.path) as other:
            revision, follower, complete = store.changes_since(None)
            assert complete
            for op in ops:
                apply(engine, other, op)
                revision, states, complete = store.changes_since(revision)
                follower = dict(states) if complete else {**follower, **states}
                disk = on_disk(engine)
                visible = {e: s for e, s in follower.items() if s.updated_at is not None}
                assert visible == disk, op
                for ex in EXERCISES:
                    assert store.state(ex) == disk.get(ex, ExerciseState.fresh(ex)), (op, ex)


def test_one_answer_rebuilds_only_its_chapter_and_reads_no_states(engine: Engine) -> None:
    """After one answer, the summary asks for no exercise of an untouched chapter and runs no
    query over the exercise states (it used to recompute everything on every answer)."""
    assert engine.progress is not None
    before = engine.summary()
    engine.submit("basics/distance", "1e9")  # a wrong answer: `next` stays where it was
    asked: list[str] = []
    course_exercise = engine.course.exercise

    def spy(exercise_id: str) -> Any:
        asked.append(exercise_id)
        return course_exercise(exercise_id)

    queries: list[str] = []
    conn: sqlite3.Connection = engine.progress._db()
    engine.course.exercise = spy  # type: ignore[method-assign]
    conn.set_trace_callback(queries.append)
    try:
        after = engine.summary()
    finally:
        conn.set_trace_callback(None)
        del engine.course.exercise
    assert after == engine.summary_full()
    assert after[0]["exercises"][0]["attempts"] == before[0]["exercises"][0]["attempts"] + 1
    assert asked and all(e.startswith("basics/") for e in asked), asked
    assert not [q for q in queries if "exercise_state" in q], queries
    assert after[1] == before[1]


def test_callers_get_copies(engine: Engine) -> None:
    first = engine.summary()
    first[0]["exercises"][0]["status"] = "solved"
    first[0]["solved"] = 99
    assert engine.summary() == engine.summary_full()
