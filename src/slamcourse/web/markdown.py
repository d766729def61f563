"""Markdown → HTML for the browser: CommonMark with raw HTML disabled, ``$…$`` kept intact.

Math is left as ``<span class="math inline">`` / ``<div class="math block">`` holding the
escaped TeX; the page typesets it with the vendored KaTeX. Raw HTML in the source (a prompt, a
feedback message quoting a learner's answer) is escaped, never passed through.

A fenced block ```{figure} ID``` (chapter prose) becomes a ``<figure>``: the SVG the plots
registry draws for ``ID`` (our own markup, its text XML-escaped where it is built, with
``role="img"``, a ``<title>`` and a ``<desc>``) and the block's content, Markdown, as its
``<figcaption>``.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import Any

from markdown_it import MarkdownIt
from markdown_it.renderer import RendererHTML
from markupsafe import Markup, escape

from slamcourse.course.loader import figure_id


@functools.cache
def _parser() -> MarkdownIt:
    from mdit_py_plugins.dollarmath import dollarmath_plugin

    md = MarkdownIt("commonmark", {"html": False, "typographer": False})
    md.use(dollarmath_plugin, allow_space=True, double_inline=True)
    md.enable("table")
    renderer = md.renderer
    assert isinstance(renderer, RendererHTML)
    default_fence = renderer.rules["fence"]

    def fence(self: Any, tokens: Sequence[Any], idx: int, options: Any, env: Any) -> str:
        fig_id = figure_id(tokens[idx].info.strip())
        if fig_id is None:
            return str(default_fence(tokens, idx, options, env))
        return figure_html(fig_id, tokens[idx].content)

    md.add_render_rule("fence", fence)
    return md


def figure_html(fig_id: str, caption: str) -> str:
    """A prose figure as HTML: the drawing and its caption (Markdown) in a ``<figure>``. A
    figure that cannot be drawn (an unknown id, a drawing bug; `slamcourse validate` reports
    both) is a visible note instead, so the rest of the chapter is still served."""
    from slamcourse.plots.registry import figure_svg

    try:
        svg = figure_svg(fig_id)
    except Exception:  # a drawing bug must not take the chapter down with it
        svg = None
    anchor = "figure-" + "".join(c if c.isalnum() else "-" for c in fig_id)
    caption_html = _parser().render(caption.strip()) if caption.strip() else ""
    if svg is None:
        return (
            f'<p class="figure-missing" id="{anchor}">[figure {escape(fig_id)} cannot be '
            "drawn]</p>\n"
        )
    return (
        f'<figure class="figure prose-figure" id="{anchor}" data-figure="{escape(fig_id)}">'
        f"{svg}<figcaption>{caption_html}</figcaption></figure>\n"
    )


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
