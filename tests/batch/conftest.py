"""A small class of submissions against the fixture course, written as an instructor would."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from slamcourse.batch.submission import FORMAT, MANIFEST, code_path, course_hash, learner_id
from slamcourse.course.loader import load_course
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind
from slamcourse.progress import variant_seed_for
from tests.conftest import FIXTURE_COURSE

COURSE = load_course(FIXTURE_COURSE)
CODE_ID = "basics/range-bearing"
SOLUTION = (FIXTURE_COURSE / "exercises/basics/solutions/range_bearing.py").read_text()


def seed_of(learner_seed: int, exercise_id: str) -> int:
    spec = COURSE.exercise(exercise_id)
    return variant_seed_for(learner_seed, exercise_id) if spec.has_variants else 0


def right_answer(learner_seed: int, exercise_id: str) -> str:
    """The accepted answer of this learner's variant, from the reference code."""
    spec = COURSE.exercise(exercise_id)
    value = get_kind(spec.kind).expected(spec, variant(spec, seed_of(learner_seed, exercise_id)))
    return json.dumps(value.tolist() if hasattr(value, "tolist") else value)


def make_submission(
    where: Path,
    learner_seed: int,
    answers: dict[str, str],
    code: str | None = None,
    *,
    manifest: dict[str, Any] | None = None,
) -> Path:
    """A submission folder: text ``answers`` on the learner's own variants, ``code`` for the
    code exercise; ``manifest`` entries override the manifest's fields."""
    where.mkdir(parents=True)
    items: list[dict[str, Any]] = [
        {"exercise": ex, "variant": seed_of(learner_seed, ex), "answer": text, "attempts": 2}
        for ex, text in answers.items()
    ]
    if code is not None:
        items.append({"exercise": CODE_ID, "variant": 0, "file": code_path(CODE_ID)})
        (where / "code" / "basics").mkdir(parents=True)
        (where / code_path(CODE_ID)).write_text(code)
    data = {
        "format": FORMAT,
        "learner": {"id": learner_id(learner_seed), "name": None, "seed": learner_seed},
        "engine": "0.1.0",
        "course": {"version": "custom", "hash": course_hash(FIXTURE_COURSE)},
        "created": None,
        "answers": items,
        **(manifest or {}),
    }
    (where / MANIFEST).write_text(json.dumps(data, indent=2))
    return where


@pytest.fixture
def options() -> Any:
    from slamcourse.batch.grade import GradeOptions

    return GradeOptions(course=FIXTURE_COURSE)
