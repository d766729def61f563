"""Fixtures of the notebook face: the fixture course, a learner's home, right answers."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from slamcourse.engine import Engine
from slamcourse.kinds import get_kind
from slamcourse.settings import Settings
from tests.conftest import FIXTURE_COURSE

CODE_ID = "basics/range-bearing"
SOLUTION = (FIXTURE_COURSE / "exercises/basics/solutions/range_bearing.py").read_text()
WRONG_SOLUTION = SOLUTION.replace(" - theta", "")  # forgets the heading: a plausible mistake


def right_answer(engine: Engine, exercise_id: str) -> str:
    """The accepted answer of the learner's own variant, from the reference code."""
    spec = engine.exercise(exercise_id)
    value = get_kind(spec.kind).expected(spec, engine.variant(exercise_id))
    return json.dumps(value.tolist() if hasattr(value, "tolist") else value)


@pytest.fixture
def course_env(private_home: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The fixture course for every engine this test opens (a kernel's too)."""
    monkeypatch.setenv("SLAMCOURSE_COURSE", str(FIXTURE_COURSE))
    monkeypatch.setenv("SLAMCOURSE_WORKSPACE", str(private_home / "workspace"))
    return private_home


@pytest.fixture
def engine(course_env: Path) -> Iterator[Engine]:
    with Engine.open(Settings.from_env()) as eng:
        yield eng


@pytest.fixture
def nb(engine: Engine) -> Iterator[Any]:
    """The notebook face on this test's engine."""
    import slamcourse.notebook as face

    face.use(engine)
    yield face
    face.use(None)
