"""Markdown → HTML for the browser: CommonMark with raw HTML disabled, ``$…$`` kept intact.

Math is left as ``<span class="math inline">`` / ``<div class="math block">`` holding the
escaped TeX; the page typesets it with the vendored KaTeX. Raw HTML in the source (a prompt, a
feedback message quoting a learner's answer) is escaped, never passed through.
"""

from __future__ import annotations

import functools

from markdown_it import MarkdownIt
from markupsafe import Markup


@functools.cache
def _parser() -> MarkdownIt:
    from mdit_py_plugins.dollarmath import dollarmath_plugin

    md = MarkdownIt("commonmark", {"html": False, "typographer": False})
    md.use(dollarmath_plugin, allow_space=True, double_inline=True)
    md.enable("table")
    return md


def to_html(text: str | None) -> Markup:
    """Safe HTML for ``text`` (empty for None)."""
    if not text:
        return Markup("")
    return Markup(_parser().render(text))


def to_inline_html(text: str | None) -> Markup:
    """Like :func:`to_html` for a one-line text (an option, a step): without the ``<p>``."""
    if not text:
        return Markup("")
    return Markup(_parser().renderInline(text))
