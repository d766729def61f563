"""Markdown → HTML for notebook outputs: CommonMark with raw HTML disabled, math left as
``$…$`` / ``$$…$$`` text for the notebook's own MathJax (JupyterLab typesets the math in an
HTML output), and the same Markdown → plain text the terminal shows (math as Unicode).

Raw HTML in a text (a prompt, feedback quoting a learner's answer) is escaped, never passed
through; the TeX of a math span is escaped too (``a<b`` stays text for MathJax).
"""

from __future__ import annotations

import functools
import html
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from markdown_it import MarkdownIt


def _math_rule(delimiter: str, block: bool) -> Any:
    def render(self: Any, tokens: Any, idx: int, options: Any, env: Any) -> str:
        tex = html.escape(tokens[idx].content, quote=False)
        if block:
            return f'<div class="slamcourse-math">{delimiter}{tex.strip()}{delimiter}</div>\n'
        return f"{delimiter}{tex}{delimiter}"

    return render


@functools.cache
def _parser() -> MarkdownIt:
    from markdown_it import MarkdownIt
    from mdit_py_plugins.dollarmath import dollarmath_plugin

    md = MarkdownIt("commonmark", {"html": False, "typographer": False})
    md.use(dollarmath_plugin, allow_space=True, double_inline=True)
    md.enable("table")
    md.add_render_rule("math_inline", _math_rule("$", False))
    md.add_render_rule("math_inline_double", _math_rule("$$", False))
    md.add_render_rule("math_block", _math_rule("$$", True))
    md.add_render_rule("math_block_label", _math_rule("$$", True))
    return md


def to_html(text: str | None) -> str:
    """Safe HTML for Markdown ``text`` (empty for None), its math kept as ``$…$``."""
    if not text:
        return ""
    return str(_parser().render(text))


def to_inline_html(text: str | None) -> str:
    """Like :func:`to_html` for a one-line text (a title, an option): without the ``<p>``."""
    if not text:
        return ""
    return str(_parser().renderInline(text))


def to_text(text: str | None, width: int = 88) -> str:
    """Markdown as the terminal shows it without colour: wrapped, math as Unicode."""
    if not text:
        return ""
    from slamcourse.render.terminal import render_markdown

    return render_markdown(text, width=width, color=False)


def escape(text: object) -> str:
    return html.escape(str(text), quote=True)
