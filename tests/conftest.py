"""Shared fixtures: the fixture course, a private learner home, and course copies to break."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from slamcourse.settings import activate_cache

FIXTURE_COURSE = Path(__file__).parent / "fixtures" / "course"
REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(autouse=True)
def private_home(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Every test gets its own progress folder; the real one is never touched."""
    home = tmp_path_factory.mktemp("home")
    monkeypatch.setenv("SLAMCOURSE_HOME", str(home))
    monkeypatch.delenv("SLAMCOURSE_COURSE", raising=False)
    monkeypatch.setenv("NO_COLOR", "1")
    activate_cache(home / "cache")  # what Engine.open does: caches live in the learner's home
    return home


@pytest.fixture
def course_copy(tmp_path: Path) -> Path:
    """A writable copy of the fixture course, for tests that break it on purpose."""
    target = tmp_path / "course"
    shutil.copytree(FIXTURE_COURSE, target)
    return target
