"""Fixtures of the browser face: an engine on the fixture course, a test client, a live server
and (for tests marked ``browser``) Debian's chromium driven by Playwright."""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from slamcourse.engine import Engine
from slamcourse.settings import Settings
from tests.conftest import FIXTURE_COURSE

TOKEN = "test-token-0123456789"
HOST = "localhost"  # what Flask's test client sends
CHROMIUM = os.environ.get("SLAMCOURSE_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--disable-quic",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


def settings_for(tmp: Path, course: Path | None = FIXTURE_COURSE) -> Settings:
    return Settings.from_env(course=course, home=tmp / "home", workspace=tmp / "workspace")


@pytest.fixture
def engine(tmp_path: Path) -> Iterator[Engine]:
    with Engine.open(settings_for(tmp_path)) as eng:
        yield eng


@pytest.fixture
def client(engine: Engine) -> Any:
    from slamcourse.web.app import create_app

    app = create_app(engine, token=TOKEN, hosts=[HOST, "127.0.0.1:5000"])
    c = app.test_client()
    return c


def _browser_usable() -> bool:
    try:
        import playwright  # noqa: F401
    except ImportError:
        return False
    return os.path.exists(CHROMIUM)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Browser tests skip where chromium (or Playwright) is missing, but never under CI."""
    if _browser_usable() or os.environ.get("CI"):
        return
    skip = pytest.mark.skip(reason=f"no chromium at {CHROMIUM} or no playwright (set CI to fail)")
    for item in items:
        if "browser" in item.keywords:
            item.add_marker(skip)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Iterator[None]:
    outcome = yield
    report = outcome.get_result()  # type: ignore[attr-defined]
    if report.when == "call":
        item.stash[_FAILED] = report.failed


_FAILED = pytest.StashKey[bool]()


@pytest.fixture(scope="module")
def live(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Any]:
    """One server on the fixture course for a test module (tests use distinct exercises)."""
    from slamcourse.web.server import running

    tmp = tmp_path_factory.mktemp("live")
    with Engine.open(settings_for(tmp)) as eng, running(eng, token=TOKEN) as srv:
        eng.start_workers()  # as `slamcourse serve` does: a warm sandbox worker
        srv.engine = eng  # type: ignore[attr-defined]
        srv.settings = eng.settings  # type: ignore[attr-defined]
        yield srv


@pytest.fixture
def page(browser: Any, live: Any, request: pytest.FixtureRequest) -> Iterator[Any]:
    """A fresh browser context that has opened the tokened address once (so holds the cookie).
    On failure a screenshot is saved and its path printed."""
    context = browser.new_context(viewport={"width": 1200, "height": 900})
    pg = context.new_page()
    pg.set_default_timeout(10_000)
    errors: list[str] = []
    pg.on("pageerror", lambda exc: errors.append(str(exc)))
    pg.goto(live.url)
    pg.js_errors = errors
    yield pg
    if request.node.stash.get(_FAILED, False):
        shots = Path(tempfile.mkdtemp(prefix="slamcourse-shots-"))
        path = shots / (request.node.name.replace("/", "_") + ".png")
        pg.screenshot(path=str(path), full_page=True)
        print(f"\nscreenshot of the failing page: {path}")
    context.close()
    assert not errors, f"JavaScript errors on the page: {errors}"
