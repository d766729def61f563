"""Progress in the browser (issue 15, item 15): the overall total and per-chapter bars, no "Give
up" on a solved exercise, the given-up mark the terminal's own, and "Next exercise" after an
answer going on in the same chapter. Its own module, so its own live server: the totals start at
zero. The tests run in file order on that one server."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from typing import Any

import pytest

from tests.conftest import FIXTURE_COURSE
from tests.web.test_browser import open_chapter, section

pytestmark = pytest.mark.browser


def bars(page: Any) -> dict[str, tuple[str, str]]:
    """Each progress bar's (value, max), by chapter id ("" for the overall one)."""
    out = {}
    for bar in page.locator("progress.bar").all():
        key = bar.get_attribute("data-bar") or ""
        out[key] = (bar.evaluate("b => String(b.value)"), bar.evaluate("b => String(b.max)"))
    return out


def test_total_and_bars_after_solving_one_exercise(page: Any, live: Any) -> None:
    open_chapter(page, live)
    assert page.locator("[data-overall]").inner_text() == "0/15"
    assert bars(page) == {"": ("0", "15"), "basics": ("0", "11"), "boundaries": ("0", "4")}
    p = live.engine.pose("basics/distance").variant.params
    sec = section(page, "basics/distance")
    sec.locator("[data-input]").fill(repr(math.hypot(p["dx"], p["dy"])))
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--distance .feedback.is-passed").wait_for()
    assert page.locator("[data-overall]").inner_text() == "1/15"
    assert bars(page) == {"": ("1", "15"), "basics": ("1", "11"), "boundaries": ("0", "4")}
    assert sec.locator("[data-giveup]").is_hidden()  # solved: nothing to give up
    open_chapter(page, live)  # as the server draws it
    assert page.locator("[data-overall]").inner_text() == "1/15"
    assert bars(page) == {"": ("1", "15"), "basics": ("1", "11"), "boundaries": ("0", "4")}
    assert section(page, "basics/distance").locator("[data-giveup]").is_hidden()
    assert section(page, "basics/heading").locator("[data-giveup]").is_visible()


def test_given_up_mark_is_the_terminals(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/count")
    sec.locator("[data-giveup]").click()
    sec.locator("[data-giveup]").click()  # "Really give up? Click again"
    page.locator("#ex-basics--count.status-given_up").wait_for()
    badge = sec.locator("[data-badge]").inner_text()
    side = page.locator('[data-status-of="basics/count"] .mark').inner_text()
    assert sec.locator("[data-giveup]").is_hidden()
    env = dict(os.environ, NO_COLOR="1", COLUMNS="100", SLAMCOURSE_HOME=str(live.settings.home))
    listing = subprocess.run(
        [sys.executable, "-m", "slamcourse", "--course", str(FIXTURE_COURSE), "list"],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    row = next(line for line in listing.splitlines() if "basics/count" in line)
    terminal_mark = row.split()[0]
    assert badge == f"{terminal_mark} given up"
    assert side == terminal_mark
    assert f"{terminal_mark} given up" in listing  # the terminal's legend says the same word
    legend = page.locator("[data-legend]").inner_text()
    assert f"{terminal_mark} given up" in legend


def test_next_exercise_after_an_answer_goes_on_in_the_same_chapter(page: Any, live: Any) -> None:
    open_chapter(page, live)
    sec = section(page, "basics/bug")
    sec.locator('[data-line="3"]').click()
    page.locator("#ex-basics--bug .feedback.is-passed").wait_for()
    link = sec.locator("[data-feedback] a.button")
    assert (link.get_attribute("href") or "").endswith("#ex-basics--range-bearing")
