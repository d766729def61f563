"""The browser face on a phone-sized screen (390 px wide), and the code editor by keyboard.

Marked ``browser`` (Debian's chromium through Playwright, as in test_browser.py).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from slamcourse.engine import Engine
from tests.web.conftest import TOKEN

pytestmark = pytest.mark.browser

WIDTH = 390


@pytest.fixture
def phone(browser: Any, live: Any) -> Iterator[Any]:
    context = browser.new_context(viewport={"width": WIDTH, "height": 844})
    pg = context.new_page()
    pg.set_default_timeout(10_000)
    errors: list[str] = []
    pg.on("pageerror", lambda exc: errors.append(str(exc)))
    pg.goto(live.url)
    yield pg
    context.close()
    assert not errors, f"JavaScript errors on the page: {errors}"


def _open(page: Any, base: str, chapter: str) -> None:
    page.goto(base + "chapter/" + chapter)
    page.wait_for_selector("html[data-ready='1']")


def _check_narrow_chapter(page: Any, title: str) -> None:
    width = page.evaluate("document.scrollingElement.scrollWidth")
    assert width <= WIDTH, f"the page lays out {width} px wide on a {WIDTH} px screen"
    heading = page.locator("main h1")
    assert heading.count() == 1 and heading.is_visible()
    assert title in heading.inner_text()
    box = heading.bounding_box()
    assert box["x"] >= 0 and box["x"] + box["width"] <= WIDTH  # not cut off
    # the lesson comes first, in reading order and on screen; the chapter list after it
    lesson_first = page.evaluate(
        "Boolean(document.querySelector('main').compareDocumentPosition("
        "document.querySelector('nav.sidebar')) & Node.DOCUMENT_POSITION_FOLLOWING)"
    )
    assert lesson_first
    main_box = page.locator("main").bounding_box()
    nav_box = page.locator("nav.sidebar").bounding_box()
    assert main_box["y"] < nav_box["y"]


def test_chapter_fits_a_phone_with_its_title_and_the_lesson_first(phone: Any, live: Any) -> None:
    _open(phone, live.base, "basics")
    _check_narrow_chapter(phone, "Fixture basics")


def test_bundled_chapters_fit_a_phone(browser: Any, tmp_path_factory: Any) -> None:
    """The real course's chapters (long formulas, code, tables) at 390 px: nothing sideways."""
    from slamcourse.web.server import running
    from tests.conftest import REPO
    from tests.web.conftest import settings_for

    tmp = tmp_path_factory.mktemp("bundled-narrow")
    with Engine.open(settings_for(tmp, REPO)) as eng, running(eng, token=TOKEN) as srv:
        context = browser.new_context(viewport={"width": WIDTH, "height": 844})
        page = context.new_page()
        page.goto(srv.url)
        for ch in eng.chapters()[:3]:
            _open(page, srv.base, ch.id)
            _check_narrow_chapter(page, ch.title)
        context.close()


def test_tab_leaves_the_code_editor_and_the_way_to_indent_is_shown(page: Any, live: Any) -> None:
    page.goto(live.base + "chapter/basics")
    page.wait_for_selector("html[data-ready='1']")
    sec = page.locator('section[data-exercise="basics/range-bearing"]')
    editor = sec.locator(".cm-content")
    editor.click()
    before = editor.inner_text()
    page.keyboard.press("Tab")
    assert editor.inner_text() == before  # nothing inserted...
    focused_in_editor = page.evaluate("Boolean(document.activeElement.closest('.cm-editor'))")
    assert not focused_in_editor  # ...and focus moved on, as for any other control
    help_text = sec.locator("[data-editor-help]")
    assert help_text.is_visible()
    assert "Tab" in help_text.inner_text() and "Ctrl+M" in help_text.inner_text()
    # Ctrl+M makes Tab indent (and says so); Ctrl+M again gives Tab back to the page
    editor.click()
    page.keyboard.press("Control+m")
    assert "indents" in help_text.inner_text()
    page.keyboard.press("End")
    page.keyboard.press("Tab")
    assert editor.inner_text() != before
    assert page.evaluate("Boolean(document.activeElement.closest('.cm-editor'))")
    page.keyboard.press("Control+m")
    page.keyboard.press("Tab")
    assert not page.evaluate("Boolean(document.activeElement.closest('.cm-editor'))")
