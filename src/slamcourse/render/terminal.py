"""Render chapter prose and exercise prompts (Markdown with LaTeX math) as terminal text.

Parsing is markdown-it-py with the ``dollarmath``, ``front_matter`` and table rules; math spans are
tokens of their own, so ``$x^*$ and $y_*$`` never meets the emphasis rule, and a math span is an
atomic word when wrapping. Styling is a handful of SGR codes written here (no rich: its import
alone costs more than the whole renderer). markdown-it is imported on the first render, not when
this module is imported.
"""

from __future__ import annotations

import os
import re

from slamcourse.course.loader import directive_id, figure_id
from slamcourse.render.math import _sanitize, latex_to_unicode, text_width

__all__ = [
    "figure_writer",
    "render_code_listing",
    "render_markdown",
    "style",
    "terminal_width",
    "use_color",
]

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path
    from typing import TextIO

    from markdown_it import MarkdownIt
    from markdown_it.tree import SyntaxTreeNode

# --------------------------------------------------------------------------- colour

_SGR = {
    "bold": "1", "dim": "2", "italic": "3", "underline": "4", "reverse": "7", "strike": "9",
    "red": "31", "green": "32", "yellow": "33", "blue": "34", "magenta": "35", "cyan": "36",
}  # fmt: skip


def style(text: str, *names: str, color: bool) -> str:
    """Wrap ``text`` in the SGR codes for ``names`` (``"bold"``, ``"red"``, ...).

    Returns ``text`` unchanged when ``color`` is False (or when there is nothing to style).
    Unknown names raise ``ValueError`` so that typos show up in tests.
    """
    codes = []
    for name in names:
        code = _SGR.get(name)
        if code is None:
            raise ValueError(f"unknown style {name!r}; known: {', '.join(_SGR)}")
        codes.append(code)
    if not color or not codes or not text:
        return text
    return f"\x1b[{';'.join(codes)}m{text}\x1b[0m"


def use_color(stream: TextIO) -> bool:
    """Whether to write ANSI colour to ``stream``.

    ``NO_COLOR`` (present and non-empty, per no-color.org) turns colour off and wins over
    everything; a non-empty ``FORCE_COLOR`` turns it on; otherwise ``TERM=dumb`` or a stream
    that is not a TTY turns it off.
    """
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    if os.environ.get("TERM") == "dumb":
        return False
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty()) if callable(isatty) else False
    except (OSError, ValueError):  # closed or detached streams
        return False


def terminal_width(stream: TextIO | None = None) -> int:
    """Columns to render for: ``COLUMNS``, else the terminal's size, clamped to [40, 100]."""
    width = 0
    columns = os.environ.get("COLUMNS", "")
    if columns.strip().isdigit():
        width = int(columns)
    if width <= 0 and stream is not None:
        try:
            width = os.get_terminal_size(stream.fileno()).columns
        except (AttributeError, OSError, ValueError):
            width = 0
    if width <= 0:
        import shutil

        width = shutil.get_terminal_size((80, 24)).columns
    return max(40, min(100, width))


# --------------------------------------------------------------------------- code listing


def render_code_listing(code: str, *, color: bool = False, highlight: int | None = None) -> str:
    """The code with right-aligned line numbers: ``  6 │ const d2 = …``.

    ``highlight`` (1-based) marks one line with ``>`` (and bold yellow when ``color``).
    """
    lines = _sanitize(code.expandtabs(4)).splitlines()
    digits = len(str(len(lines)))
    out = []
    for number, line in enumerate(lines, start=1):
        marked = number == highlight
        gutter = f"{'>' if marked else ' '} {number:>{digits}} │"
        text = (gutter + " " + line).rstrip()
        if not color:
            out.append(text)
        elif marked:
            out.append(
                style(gutter, "bold", "yellow", color=True)
                + style((" " + line).rstrip(), "bold", color=True)
            )
        else:
            out.append(style(gutter, "dim", color=True) + (" " + line).rstrip())
    return "\n".join(out)


# --------------------------------------------------------------------------- markdown

_PARSER: MarkdownIt | None = None


def _parser() -> MarkdownIt:
    """The shared markdown-it instance (built on first use: markdown-it imports ~40 ms)."""
    global _PARSER
    if _PARSER is None:
        from markdown_it import MarkdownIt
        from mdit_py_plugins.dollarmath import dollarmath_plugin
        from mdit_py_plugins.front_matter import front_matter_plugin

        md = MarkdownIt("commonmark").enable(["table", "strikethrough"])
        md.use(front_matter_plugin)
        md.use(dollarmath_plugin, allow_digits=False, double_inline=True)
        _PARSER = md
    return _PARSER


# A piece of inline text: (text, styles). Words are lists of pieces; _BREAK forces a new line.
_Piece = tuple[str, tuple[str, ...]]
_BREAK: list[_Piece] = []


class _Inline:
    """Inline content flattened into words that wrapping never splits."""

    def __init__(self) -> None:
        self.words: list[list[_Piece]] = []
        self.current: list[_Piece] = []

    def text(self, text: str, styles: tuple[str, ...]) -> None:
        parts = text.split(" ")
        for k, part in enumerate(parts):
            if k:
                self.end_word()
            if part:
                self.current.append((part, styles))

    def atom(self, text: str, styles: tuple[str, ...]) -> None:
        if text:
            self.current.append((text, styles))

    def end_word(self) -> None:
        if self.current:
            self.words.append(self.current)
            self.current = []

    def line_break(self) -> None:
        self.end_word()
        self.words.append(_BREAK)

    def finish(self) -> list[list[_Piece]]:
        self.end_word()
        return self.words


def _wrap(words: list[list[_Piece]], width: int) -> list[list[_Piece]]:
    """Greedy fill; a word wider than ``width`` gets a line of its own."""
    lines: list[list[_Piece]] = []
    line: list[_Piece] = []
    used = 0
    started = False
    for word in words:
        if word is _BREAK:
            lines.append(line)
            line, used, started = [], 0, True
            continue
        size = sum(text_width(text) for text, _ in word)
        if line and used + 1 + size > width:
            lines.append(line)
            line, used = [], 0
        if line:
            prev_styles = line[-1][1]
            shared = tuple(s for s in prev_styles if s in word[0][1])
            line.append((" ", shared))
            used += 1
        line.extend(word)
        used += size
        started = True
    if line or not started:
        lines.append(line)
    return lines


def _wrapped(words: list[list[_Piece]], width: int, color: bool) -> list[str]:
    """``words`` filled into lines of ``width`` columns (:func:`_wrap`), as text (:func:`_join`)."""
    return [_join(line, color) for line in _wrap(words, width)]


def _join(line: list[_Piece], color: bool) -> str:
    """One wrapped line as text, consecutive pieces with the same styles styled together."""
    if not color:
        return "".join(text for text, _ in line)
    out: list[str] = []
    run: list[str] = []
    run_styles: tuple[str, ...] = ()
    for text, styles in line:
        if styles != run_styles and run:
            out.append(style("".join(run), *run_styles, color=True))
            run = []
        run_styles = styles
        run.append(text)
    if run:
        out.append(style("".join(run), *run_styles, color=True))
    return "".join(out)


class _Markdown:
    """Walks markdown-it's syntax tree, producing lines of terminal text."""

    def __init__(
        self,
        color: bool,
        exercise: Callable[[str], str] | None,
        figure: Callable[[str], str | None] | None = None,
    ) -> None:
        self.color = color
        self.exercise = exercise
        self.figure = figure
        self.list_depth = 0

    # ---- inline
    def inline(
        self, children: list[SyntaxTreeNode], acc: _Inline, styles: tuple[str, ...] = ()
    ) -> None:
        """Append inline nodes to ``acc`` as words (math and code spans are atomic)."""
        for child in children:
            kind = child.type
            if kind == "text":
                acc.text(child.content, styles)
            elif kind == "softbreak":
                acc.end_word()
            elif kind == "hardbreak":
                acc.line_break()
            elif kind == "em":
                self.inline(child.children, acc, (*styles, "italic"))
            elif kind == "strong":
                self.inline(child.children, acc, (*styles, "bold"))
            elif kind == "s":
                self.inline(child.children, acc, (*styles, "strike"))
            elif kind == "code_inline":
                acc.atom("`" + child.content + "`", (*styles, "cyan"))
            elif kind in ("math_inline", "math_inline_double"):
                acc.atom(latex_to_unicode(child.content), styles)
            elif kind == "link":
                self.link(child, acc, styles)
            elif kind == "image":
                alt = _plain_text(child) or str(child.attrs.get("alt", "") or "")
                acc.atom("[image: " + alt + "]" if alt else "[image]", (*styles, "dim"))
            elif kind == "html_inline":
                if not child.content.startswith("<!--"):
                    acc.atom(child.content, styles)
            elif child.children:
                self.inline(child.children, acc, styles)
            else:
                acc.text(child.content, styles)

    def link(self, node: SyntaxTreeNode, acc: _Inline, styles: tuple[str, ...]) -> None:
        href = str(node.attrs.get("href", "") or "")
        text = _plain_text(node)
        if node.markup == "autolink" or not text or text == href or "mailto:" + text == href:
            acc.atom(href if node.markup != "autolink" else text or href, (*styles, "underline"))
            return
        self.inline(node.children, acc, (*styles, "underline"))
        if href and not href.startswith("#"):
            acc.end_word()
            acc.atom("(" + href + ")", (*styles, "dim"))

    def words(self, node: SyntaxTreeNode, styles: tuple[str, ...] = ()) -> list[list[_Piece]]:
        return self.words_of(node.children, styles)

    def words_of(
        self, children: list[SyntaxTreeNode], styles: tuple[str, ...] = ()
    ) -> list[list[_Piece]]:
        acc = _Inline()
        self.inline(children, acc, styles)
        return acc.finish()

    # ---- blocks
    def blocks(self, nodes: list[SyntaxTreeNode], width: int, tight: bool = False) -> list[str]:
        """Render block nodes; blank lines between blocks unless ``tight`` (tight lists)."""
        out: list[str] = []
        for node in nodes:
            lines = self.block(node, width)
            if not lines:
                continue
            if out and not (tight and (node.type == "paragraph" or _is_list(node))):
                out.append("")
            out.extend(lines)
        return out

    def block(self, node: SyntaxTreeNode, width: int) -> list[str]:
        kind = node.type
        if kind == "paragraph":
            return self.paragraph(node, width)
        if kind == "heading":
            return self.heading(node, width)
        if kind in ("fence", "code_block"):
            return self.code(node, width)
        if kind in ("bullet_list", "ordered_list"):
            return self.list_block(node, width)
        if kind == "blockquote":
            bar = style("│", "dim", color=self.color)
            inner = self.blocks(node.children, max(1, width - 2))
            return [bar + " " + line if line else bar for line in inner]
        if kind == "table":
            return self.table(node, width)
        if kind == "hr":
            return [style("─" * width, "dim", color=self.color)]
        if kind in ("math_block", "math_block_label"):
            return self.display_math(node.content, node.info if kind == "math_block_label" else "")
        if kind == "html_block":
            content = node.content.strip("\n")
            if content.lstrip().startswith("<!--"):
                return []
            return content.splitlines()
        if kind == "front_matter":
            return []
        if node.children:
            return self.blocks(node.children, width)
        return [line.rstrip() for line in node.content.splitlines()]

    def paragraph(self, node: SyntaxTreeNode, width: int) -> list[str]:
        """Wrap a paragraph; a ``$$...$$`` inside it becomes a display block of its own."""
        inline = node.children[0] if node.children else None
        if inline is None:
            return []
        out: list[str] = []
        run: list[SyntaxTreeNode] = []

        def flush() -> None:
            words = self.words_of(run)
            run.clear()
            if any(word is not _BREAK for word in words):
                if out:
                    out.append("")
                out.extend(_wrapped(words, width, self.color))

        for child in inline.children:
            if child.type == "math_inline_double":
                flush()
                if out:
                    out.append("")
                out.extend(self.display_math(child.content, ""))
            else:
                run.append(child)
        flush()
        return out

    def heading(self, node: SyntaxTreeNode, width: int) -> list[str]:
        level = int(node.tag[1:]) if node.tag[1:].isdigit() else 1
        inline = node.children[0] if node.children else None
        if inline is None:
            return []
        words = self.words(inline, ("bold",) if level > 1 else ("bold", "underline"))
        lines = _wrap(words, width)
        out = [_join(line, self.color) for line in lines]
        if level <= 2:
            rule_width = max((sum(text_width(t) for t, _ in line) for line in lines), default=0)
            out.append(style(("═" if level == 1 else "─") * rule_width, "dim", color=self.color))
        return out

    def figure_block(self, fig_id: str, caption: str, width: int) -> list[str]:
        """A prose figure as one paragraph: that it exists, its caption, where its SVG is."""
        where = self.figure(fig_id) if self.figure is not None and fig_id else None
        if where is not None:
            tail = f"(picture written to {where})"
        else:
            tail = f"(slamcourse plot {fig_id} draws it)"
        acc = _Inline()
        acc.text("Figure:", ("bold",))
        acc.end_word()
        tree = _parse_tree(caption.strip())
        for node in tree.children:
            if node.type == "paragraph" and node.children:
                self.inline(node.children[0].children, acc, ("italic",))
                acc.end_word()
        acc.atom(tail, ("dim",))
        return _wrapped(acc.finish(), width, self.color)

    def code(self, node: SyntaxTreeNode, width: int = 80) -> list[str]:
        info = node.info.strip() if node.type == "fence" else ""
        fig_id = figure_id(info)
        if fig_id is not None:
            return self.figure_block(fig_id, node.content, width)
        ex_id = directive_id(info)
        if ex_id is not None:
            if self.exercise is None:
                return []
            text = self.exercise(ex_id)
            return text.rstrip("\n").splitlines() if text.strip() else []
        content = node.content.expandtabs(4).rstrip("\n")
        return ["    " + line if line.strip() else "" for line in content.splitlines()]

    def display_math(self, tex: str, label: str) -> list[str]:
        lines = latex_to_unicode(tex, display=True).splitlines()
        if not lines:
            return []
        if label:
            middle = (len(lines) - 1) // 2
            lines[middle] += "    (" + label + ")"
        return ["    " + line if line else "" for line in lines]

    def list_block(self, node: SyntaxTreeNode, width: int) -> list[str]:
        """Bullet (•, ◦, ▪ by depth) or numbered list, wrapped with a hanging indent."""
        self.list_depth += 1
        try:
            return self._list(node, width)
        finally:
            self.list_depth -= 1

    def _list(self, node: SyntaxTreeNode, width: int) -> list[str]:
        ordered = node.type == "ordered_list"
        items = [child for child in node.children if child.type == "list_item"]
        if ordered:
            start = node.attrs.get("start", 1)
            first = start if isinstance(start, int) else int(start) if str(start).isdigit() else 1
            markers = [f"{first + i}{node.markup or '.'}" for i in range(len(items))]
        else:
            markers = ["•◦▪"[(self.list_depth - 1) % 3]] * len(items)
        size = max((len(m) for m in markers), default=1)
        indent = size + 1
        tight = all(
            paragraph.hidden
            for item in items
            for paragraph in item.children
            if paragraph.type == "paragraph"
        )
        out: list[str] = []
        for marker, item in zip(markers, items, strict=True):
            inner = self.blocks(item.children, max(1, width - indent), tight=tight)
            if out and not tight:
                out.append("")
            head = style(marker.rjust(size), "dim" if not ordered else "bold", color=self.color)
            if not inner:
                out.append(head)
                continue
            out.append(head + " " + inner[0])
            out.extend(" " * indent + line if line else "" for line in inner[1:])
        return out

    def table(self, node: SyntaxTreeNode, width: int) -> list[str]:
        rows: list[list[list[list[_Piece]]]] = []
        aligns: list[str] = []
        header_rows = 0
        for section in node.children:
            for tr in section.children:
                cells = []
                for cell in tr.children:
                    inline = cell.children[0] if cell.children else None
                    styles = ("bold",) if cell.type == "th" else ()
                    cells.append(self.words(inline, styles) if inline is not None else [])
                    if len(rows) == 0:
                        align = str(cell.attrs.get("style", "") or "")
                        aligns.append(align.replace("text-align:", "").strip())
                rows.append(cells)
                if section.type == "thead":
                    header_rows += 1
        if not rows:
            return []
        ncols = max(len(row) for row in rows)
        aligns += [""] * (ncols - len(aligns))
        for row in rows:
            row += [[] for _ in range(ncols - len(row))]

        def natural(words: list[list[_Piece]]) -> int:
            sizes = [sum(text_width(t) for t, _ in w) for w in words if w is not _BREAK]
            return sum(sizes) + max(0, len(sizes) - 1)

        def longest(words: list[list[_Piece]]) -> int:
            return max((sum(text_width(t) for t, _ in w) for w in words), default=0)

        widths = [max(natural(row[c]) for row in rows) for c in range(ncols)]
        floors = [
            min(widths[c], max(max(longest(row[c]) for row in rows), 8)) for c in range(ncols)
        ]
        gap = 2
        while sum(widths) + gap * (ncols - 1) > width:
            shrinkable = [c for c in range(ncols) if widths[c] > floors[c]]
            if not shrinkable:
                break
            widest = max(shrinkable, key=lambda c: widths[c])
            widths[widest] -= 1
        out: list[str] = []
        for r, row in enumerate(rows):
            wrapped = [_wrap(row[c], max(1, widths[c])) for c in range(ncols)]
            height = max(len(cell) for cell in wrapped)
            for k in range(height):
                texts = []
                for c in range(ncols):
                    line = wrapped[c][k] if k < len(wrapped[c]) else []
                    pad = widths[c] - sum(text_width(t) for t, _ in line)
                    text = _join(line, self.color)
                    if aligns[c] == "right":
                        text = " " * pad + text
                    elif aligns[c] == "center":
                        text = " " * (pad // 2) + text + " " * (pad - pad // 2)
                    else:
                        text = text + " " * pad
                    texts.append(text)
                out.append((" " * gap).join(texts).rstrip())
            if r == header_rows - 1:
                rule = (" " * gap).join("─" * w for w in widths)
                out.append(style(rule, "dim", color=self.color))
        return out


def _is_list(node: SyntaxTreeNode) -> bool:
    return node.type in ("bullet_list", "ordered_list")


def _plain_text(node: SyntaxTreeNode) -> str:
    parts = []
    for child in node.children:
        if child.type in ("text", "code_inline"):
            parts.append(child.content)
        elif child.type in ("math_inline", "math_inline_double"):
            parts.append(latex_to_unicode(child.content))
        elif child.children:
            parts.append(_plain_text(child))
    return "".join(parts)


def _parse_tree(md: str) -> SyntaxTreeNode:
    from markdown_it.tree import SyntaxTreeNode

    return SyntaxTreeNode(_parser().parse(_sanitize(md)))


def figure_writer(workspace: Path) -> Callable[[str], str | None]:
    """A ``figure`` callback for :func:`render_markdown`: draws the figure into
    ``<workspace>/figures/`` and returns the file's path (None when it cannot be drawn)."""

    def write(fig_id: str) -> str | None:
        from slamcourse.plots.command import figure_file

        path = figure_file(workspace, fig_id)
        return None if path is None else str(path)

    return write


def render_markdown(
    md: str,
    *,
    width: int = 80,
    color: bool = False,
    exercise: Callable[[str], str] | None = None,
    figure: Callable[[str], str | None] | None = None,
) -> str:
    """Render Markdown with ``$...$`` / ``$$...$$`` LaTeX math as terminal text.

    Paragraphs and list items are wrapped to ``width`` (a math span or code span is never split);
    code blocks are indented, not wrapped; display math is indented, matrices laid out as grids.
    A fenced block with info string ``{exercise} ID`` is replaced by ``exercise(ID)`` (or dropped
    when ``exercise`` is None). A block ``{figure} ID`` (its content the caption) becomes one
    paragraph: "Figure", the caption, and where ``figure(ID)`` wrote its SVG (a terminal shows
    no pictures), or the command that draws it. YAML front matter is skipped. With
    ``color=False`` the output holds no escape codes (control characters in the input are
    replaced by U+FFFD).
    """
    plain = _plain_paragraphs(md)
    if plain is not None:  # (most feedback: the Markdown parser need not even be imported)
        lines: list[str] = []
        for words in plain:
            if lines:
                lines.append("")
            lines.extend(_wrapped(words, max(1, width), color))
        return "\n".join(line.rstrip() for line in lines)
    tree = _parse_tree(md)
    lines = _Markdown(color, exercise, figure).blocks(tree.children, max(1, width))
    return "\n".join(line.rstrip() for line in lines)


_PLAIN_WORD = r"[A-Za-z0-9,.;:'\"?!%/@^{}()\u00a1-\uffff]+"
_PLAIN_LINE = re.compile(f"{_PLAIN_WORD}(?: {_PLAIN_WORD})*")
"""A line Markdown reads as nothing but its words: no ASCII character of Markdown's syntax
(emphasis, code, links, images, math, HTML, entities, escapes, headings and their underlines,
lists, quotes, tables, rules), no space at either end or twice in a row (line breaks, code
blocks), no tab; ``str.isprintable`` then keeps out control characters and Unicode spaces."""
_LIST_START = re.compile(r"[0-9]+[.)]")


def _plain_paragraphs(md: str) -> list[list[list[_Piece]]] | None:
    """``md``'s paragraphs as words when every line is plain text (:data:`_PLAIN_LINE`, and not
    the start of an ordered list) and paragraphs are separated by single blank lines; None
    otherwise. Rendered through the same wrapping, such text comes out exactly as markdown-it's
    tree of it does (tests/unit/test_render.py compares the two)."""
    paragraphs: list[list[list[_Piece]]] = []
    words: list[list[_Piece]] = []
    blank = True
    for line in md.split("\n"):
        if not line:
            if blank:
                return None  # (two blank lines in a row, or one first: keep to the parser)
            paragraphs.append(words)
            words, blank = [], True
            continue
        if not _PLAIN_LINE.fullmatch(line) or _LIST_START.match(line) or not line.isprintable():
            return None
        words.extend([(word, ())] for word in line.split(" "))
        blank = False
    if words:
        paragraphs.append(words)
    return paragraphs or None
