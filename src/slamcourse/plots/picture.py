"""What a picture is: a drawing of an exercise's variant, or a figure of a chapter's prose.

Kept apart from ``registry`` so that chapter modules (``plots/ch_*.py``) can build their entries
without importing the registry that collects them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

Params = Mapping[str, Any]
Plot = Callable[[Params], str]
Figure = Callable[[], str]
"""A prose figure: no arguments (it draws the chapter's own numbers), returns SVG."""


@dataclass(frozen=True)
class Picture:
    """``draw(params, show_results)`` → SVG. ``after_solving``: the picture shows the answer
    itself (a count of cells, a value), so it appears only once the exercise is solved or given
    up; other pictures hide their derived figures (``show_results`` False) until then."""

    draw: Callable[[Params, bool], str]
    after_solving: bool = False


def given(draw: Plot) -> Picture:
    """A picture of the givens only: nothing in it is an answer."""
    return Picture(lambda p, _: draw(p))


def answer(draw: Plot) -> Picture:
    """A picture that *is* the answer: shown only once the exercise is solved or given up."""
    return Picture(lambda p, _: draw(p), after_solving=True)
