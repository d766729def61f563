"""Order feedback in a real browser (issue 15, item 11): the ids it names are the ones on the
page, its sentences are paragraphs of their own, and "Correct" is said once. Playwright drives
Debian's chromium as in test_browser.py (never `playwright install`)."""

from __future__ import annotations

import re
from typing import Any

import pytest

pytestmark = pytest.mark.browser


def test_order_feedback_names_ids_the_page_shows(page: Any, live: Any) -> None:
    page.goto(live.base + "chapter/basics")
    page.wait_for_selector("html[data-ready='1']")
    sec = page.locator('section[data-exercise="basics/steps"]')
    items = sec.locator("[data-item]")
    shown = [items.nth(i).get_attribute("data-item") for i in range(items.count())]
    visible = [items.nth(i).locator(".opt-id").inner_text().strip() for i in range(len(shown))]
    assert visible == shown  # each step shows the id a learner answers with
    fb = sec.locator("[data-feedback]")

    sec.locator("[data-check]").click()  # the order shown is never the right one
    page.locator("#ex-basics--steps .feedback.is-failed").wait_for()
    text = fb.inner_text()
    named = re.findall(r"\b([a-z])\)", text.split("Out of place:", 1)[1])
    assert named and set(named) <= set(shown), text
    for label in named:
        assert sec.locator(f'[data-item="{label}"] .opt-id').is_visible()
    # "Not quite: …", "Out of place: …" and the step's own message: paragraphs of their own
    paragraphs = fb.locator("p:not(.verdict)")
    assert paragraphs.count() >= 2
    assert paragraphs.nth(0).inner_text().startswith("Not quite:")
    assert paragraphs.nth(1).inner_text().startswith("Out of place:")

    for place, wanted in enumerate(["p", "m", "u"]):  # sort it, by keyboard
        sec.locator(f'[data-item="{wanted}"]').focus()
        order = [items.nth(i).get_attribute("data-item") for i in range(items.count())]
        for _ in range(order.index(wanted) - place):
            page.keyboard.press("Alt+ArrowUp")
    sec.locator("[data-check]").click()
    page.locator("#ex-basics--steps .feedback.is-passed").wait_for()
    assert fb.inner_text().lower().count("correct") == 1, fb.inner_text()
