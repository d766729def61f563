"""The browser face in a real browser (Debian's chromium through Playwright).

Marked ``browser``: skipped where chromium is missing, failed under CI (see conftest.py). One
server on the fixture course serves the module; each test works on its own exercise.
"""

from __future__ import annotations

import math
import urllib.error
import urllib.request
from typing import Any

import pytest

from slamcourse.engine import Engine
from tests.web.conftest import TOKEN

pytestmark = pytest.mark.browser


def open_chapter(page: Any, live: Any, chapter: str = "basics") -> None:
    page.goto(live.base + "chapter/" + chapter)
    page.wait_for_selector("html[data-ready='1']")


def section(page: Any, ex: str) -> Any:
    return page.locator(f'section[data-exercise="{ex}"]')


def feedback(sec: Any) -> Any:
    return sec.locator("[data-feedback]")


def test_number_wrong_then_right(page: Any, live: Any) -> None:
    open_chapter(page, live)
    p = live.engine.pose("basics/distance").variant.params
    d = math.hypot(p["dx"], p["dy"])
    sec = section(page, "basics/distance")
    sec.locator("[data-input]").fill(repr(d * d))
    sec.locator("[data-input]").press("Enter")
    page.wait_for_function(
        "el => el.classList.contains('is-failed')", arg=feedback(sec).element_handle()
    )
    assert "✗ Not yet" in feedback(sec).inner_text()
    assert "square root" in feedback(sec).inner_text()
    assert sec.locator("[data-explanation]").is_hidden()
    sec.locator("[data-input]").fill(repr(d))
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--distance .feedback.is-passed").wait_for()
    assert "✓ Correct" in feedback(sec).inner_text()
    assert sec.locator("[data-explanation]").is_visible()
    assert "solved" in sec.locator("[data-badge]").inner_text()
    assert "solved" in page.locator('[data-status-of="basics/distance"]').inner_text()


def test_matrix_one_wrong_cell_is_marked(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/identity")
    for cell, value in {"0,0": "1", "0,1": "0", "1,0": "7", "1,1": "1"}.items():
        sec.locator(f'[data-cell="{cell}"]').fill(value)
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--identity .feedback.is-failed").wait_for()
    assert sec.locator("input.wrong").count() == 1
    wrong = sec.locator('[data-cell="1,0"]')
    assert "wrong" in (wrong.get_attribute("class") or "")
    assert wrong.get_attribute("aria-invalid") == "true"


def test_click_the_bug_line(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/bug")
    sec.locator('[data-line="2"]').click()
    page.locator("#ex-basics--bug .feedback.is-failed").wait_for()
    assert "sum of squares is right" in feedback(sec).inner_text()
    sec.locator('[data-line="3"]').click()
    page.locator("#ex-basics--bug .feedback.is-passed").wait_for()


def test_reorder_steps_by_keyboard(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/steps")
    items = sec.locator("[data-item]")

    def order() -> list[str]:
        return [items.nth(i).get_attribute("data-item") or "" for i in range(items.count())]

    shown = order()
    assert sorted(shown) == ["m", "p", "u"] and shown != ["p", "m", "u"]  # shuffled
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--steps .feedback.is-failed").wait_for()
    # sort with the keyboard alone: focus a step, Alt+ArrowUp moves it up one place
    for place, wanted in enumerate(["p", "m", "u"]):
        sec.locator(f'[data-item="{wanted}"]').focus()
        for _ in range(order().index(wanted) - place):
            page.keyboard.press("Alt+ArrowUp")
        assert order()[place] == wanted
    assert page.evaluate("document.activeElement.dataset.item") == "u"
    page.keyboard.press("Alt+ArrowDown")  # already last: stays
    assert order() == ["p", "m", "u"]
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--steps .feedback.is-passed").wait_for()


def test_code_counterexample_and_script_shown_as_text(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/range-bearing")
    src = (
        "def range_bearing(dx, dy, theta):\n"
        "    print('<script>alert(1)</script>')\n"
        "    return '<script>alert(1)</script>'\n"
    )
    editor = sec.locator(".cm-content")  # the vendored CodeMirror editor
    assert editor.get_attribute("aria-label") == "Your Python code for range_bearing"
    editor.fill(src)
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--range-bearing .feedback.is-failed").wait_for(timeout=30_000)
    table = sec.locator(".counterexample")
    assert table.count() == 1
    assert "<script>alert(1)</script>" in table.inner_text()  # as text, not as an element
    assert page.locator("section.exercise script").count() == 0
    assert "Smallest failing input" in table.inner_text()


def test_progress_kept_on_reload(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/pick")
    sec.locator("[data-choice]", has_text="A pose graph optimiser").click()  # relabelled
    page.locator("#ex-basics--pick .feedback.is-passed").wait_for()
    page.reload()
    page.wait_for_selector("html[data-ready='1']")
    assert "solved" in section(page, "basics/pick").locator("[data-badge]").inner_text()
    assert section(page, "basics/pick").locator("[data-explanation]").is_visible()


def test_terminal_answer_shows_as_done(
    page: Any, live: Any, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """`slamcourse check` (the terminal face, its own engine) on the same progress database."""
    from slamcourse.cli import main
    from tests.conftest import FIXTURE_COURSE

    monkeypatch.setenv("SLAMCOURSE_HOME", str(live.settings.home))
    n = live.engine.pose("basics/count").variant.params["n"]
    argv = ["--course", str(FIXTURE_COURSE), "check", "basics/count", "--answer", str(3 + 2 * n)]
    assert main(argv) == 0
    assert "passed" in capsys.readouterr().out
    open_chapter(page, live)
    assert "solved" in section(page, "basics/count").locator("[data-badge]").inner_text()
    assert "solved" in page.locator('[data-status-of="basics/count"]').inner_text()
    assert section(page, "basics/count").locator("[data-explanation]").is_visible()


def test_request_without_token_refused(live: Any) -> None:
    with pytest.raises(urllib.error.HTTPError) as err:
        urllib.request.urlopen(live.base + "chapter/basics", timeout=5)
    assert err.value.code == 403
    err.value.close()
    import http.cookiejar

    opener = urllib.request.build_opener(
        urllib.request.HTTPCookieProcessor(http.cookiejar.CookieJar())
    )
    with opener.open(live.base + f"?token={TOKEN}", timeout=5) as ok:
        assert ok.status == 200  # the redirect set the cookie, which the next request carried


def test_expression_preview_and_no_katex_errors(page: Any, live: Any) -> None:
    open_chapter(page, live)
    assert page.locator(".katex").count() > 0
    assert page.locator(".katex-error").count() == 0
    sec = section(page, "basics/slope")
    sec.locator("[data-input]").fill("2*x/sqrt(x^2+1)")
    assert sec.locator("[data-preview] .katex .mfrac").count() == 1
    assert sec.locator("[data-preview] .katex .sqrt").count() == 1


def test_bundled_course_smoke(browser: Any, tmp_path_factory: Any) -> None:
    """Every chapter of the bundled course renders with all its math typeset."""
    from slamcourse.web.server import running
    from tests.conftest import REPO
    from tests.web.conftest import settings_for

    tmp = tmp_path_factory.mktemp("bundled")
    with Engine.open(settings_for(tmp, REPO)) as eng, running(eng, token=TOKEN) as srv:
        context = browser.new_context()
        page = context.new_page()
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(srv.url)
        for ch in eng.chapters():
            page.goto(srv.base + "chapter/" + ch.id)
            page.wait_for_selector("html[data-ready='1']")
            assert page.locator(".katex").count() > 0, ch.id
            assert page.locator(".katex-error").count() == 0, ch.id
            assert page.locator("section.exercise").count() == len(ch.exercise_ids)
        context.close()
        assert not errors
