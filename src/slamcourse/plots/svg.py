"""A small SVG writer: every picture is a string built from numbers, with a text alternative.

Each figure starts with ``<title>`` and ``<desc>`` (what a screen reader announces, through
``role="img"`` and ``aria-labelledby``); text is XML-escaped here, so callers pass plain text.
Colours are never the only signal: every series also differs in dash pattern or marker and is
named in a legend and in the description.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Sequence
from xml.sax.saxutils import escape, quoteattr


def fmt(x: float) -> str:
    """A coordinate or label number: at most 2 decimals, no trailing zeros, no ``-0``."""
    text = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def num(x: float, digits: int = 3) -> str:
    """A number for a reader: ``digits`` significant figures."""
    text = f"{x:.{digits}g}"
    return text.replace("-", "−")


def attrs(**kw: object) -> str:
    """``key="value"`` pairs; ``stroke_width`` becomes ``stroke-width``; None is left out."""
    return " ".join(
        f"{k.rstrip('_').replace('_', '-')}={quoteattr(fmt(v) if isinstance(v, float) else str(v))}"
        for k, v in kw.items()
        if v is not None
    )


def el(tag: str, body: str = "", /, **kw: object) -> str:
    a = attrs(**kw)
    head = f"<{tag} {a}" if a else f"<{tag}"
    return f"{head}>{body}</{tag}>" if body else f"{head}/>"


def text(x: float, y: float, content: str, **kw: object) -> str:
    return el("text", escape(content), x=float(x), y=float(y), **kw)


def polyline(points: Iterable[tuple[float, float]], **kw: object) -> str:
    pts = " ".join(f"{fmt(x)},{fmt(y)}" for x, y in points)
    return el("polyline", points=pts, fill="none", **kw)


def document(width: float, height: float, title: str, desc: str, body: Sequence[str]) -> str:
    """A standalone ``<svg>`` element with its text alternative (also valid inline in HTML).

    The ids its ``aria-labelledby`` names come from its content: the same numbers give the same
    SVG, and two different pictures inlined in one page never share an id."""
    n = hashlib.sha1("".join([title, desc, *body]).encode()).hexdigest()[:10]
    tid, did = f"plot-title-{n}", f"plot-desc-{n}"
    head = (
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {fmt(width)} {fmt(height)}" '
        f'width="{fmt(width)}" height="{fmt(height)}" role="img" class="plot" '
        f'aria-labelledby="{tid} {did}" font-family="sans-serif" font-size="12">'
    )
    return "".join(
        [
            head,
            f'<title id="{tid}">{escape(title)}</title>',
            f'<desc id="{did}">{escape(desc)}</desc>',
            *body,
            "</svg>",
        ]
    )
