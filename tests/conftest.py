"""Shared fixtures: the fixture course, a private learner home, and course copies to break."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

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


@pytest.fixture(scope="session")
def browser() -> Iterator[Any]:
    """One chromium for the whole session, shared by every browser test (tests/web,
    tests/notebook): Playwright's sync API runs one event loop per thread, so a second
    ``sync_playwright()`` while this one is open would refuse to start."""
    from playwright.sync_api import sync_playwright

    from tests.web.conftest import CHROMIUM, CHROMIUM_ARGS

    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield b
        b.close()
