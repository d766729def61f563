"""Matrices drawn as grids: block structure (Σ, Ω, P), non-zero patterns, values.

A matrix is drawn cell by cell; ``blocks`` (name, size) groups rows and columns into the state's
blocks (the robot's pose, each landmark), with their names along the top and the left. A cell
is shaded by its kind (a dict from (row, col) to a kind) and its kinds are named in a legend;
``values`` writes each cell's number in it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from slamcourse.plots.canvas import INK, MUTED, legend_box, text_width
from slamcourse.plots.svg import el, num, text

Kinds = Mapping[str, tuple[str, str]]  # kind → (fill colour, legend name)


def matrix_panel(
    x0: float,
    y0: float,
    n: int,
    cell: float,
    kinds: Mapping[tuple[int, int], str],
    styles: Kinds,
    *,
    blocks: Sequence[tuple[str, int]] = (),
    values: Sequence[Sequence[float]] | None = None,
    caption: str = "",
    marks: Mapping[tuple[int, int], str] | None = None,
) -> list[str]:
    """One n × n matrix with its top-left corner at (x0, y0) px."""
    out: list[str] = []
    if caption:
        out.append(text(x0, y0 - 26 if blocks else y0 - 8, caption, fill=INK, font_weight="bold"))
    out.append(el("rect", x=x0, y=y0, width=cell * n, height=cell * n, fill="#fff", stroke="#888"))
    for (i, j), kind in sorted(kinds.items()):
        fill = styles[kind][0]
        out.append(
            el(
                "rect",
                x=x0 + j * cell + 0.5,
                y=y0 + i * cell + 0.5,
                width=cell - 1,
                height=cell - 1,
                fill=fill,
            )
        )
    if values is not None:
        for i in range(n):
            for j in range(n):
                v = float(values[i][j])
                if v == 0 and (i, j) not in kinds:
                    continue
                dark = (
                    styles[kinds[(i, j)]][0] in ("#1f4e79", "#333", "#7a3fa0", "#1f6fb2")
                    if ((i, j) in kinds)
                    else False
                )
                out.append(
                    text(
                        x0 + (j + 0.5) * cell,
                        y0 + (i + 0.5) * cell + 4,
                        num(v, 2),
                        text_anchor="middle",
                        font_size="10",
                        fill="#fff" if dark else INK,
                    )
                )
    if marks:
        for (i, j), mark in marks.items():
            out.append(
                text(
                    x0 + (j + 0.5) * cell,
                    y0 + (i + 0.5) * cell + 4,
                    mark,
                    text_anchor="middle",
                    font_size="11",
                    fill=INK,
                    font_weight="bold",
                )
            )
    at = 0
    for name, size in blocks:
        if at:
            out.append(
                el(
                    "line",
                    x1=x0 + at * cell,
                    x2=x0 + at * cell,
                    y1=y0 - 4,
                    y2=y0 + n * cell,
                    stroke=INK,
                    stroke_width=1.5,
                )
            )
            out.append(
                el(
                    "line",
                    x1=x0 - 4,
                    x2=x0 + n * cell,
                    y1=y0 + at * cell,
                    y2=y0 + at * cell,
                    stroke=INK,
                    stroke_width=1.5,
                )
            )
        mid = at + size / 2
        out.append(
            text(x0 + mid * cell, y0 - 8, name, text_anchor="middle", fill=MUTED, font_size="11")
        )
        out.append(
            text(x0 - 6, y0 + mid * cell + 4, name, text_anchor="end", fill=MUTED, font_size="11")
        )
        at += size
    return out


def matrix_legend(styles: Kinds, used: set[str], x: float, y: float) -> list[str]:
    entries = [(styles[k][1], styles[k][0], "marker:square") for k in styles if k in used]
    return legend_box(entries, x, y) if entries else []


def legend_width(styles: Kinds) -> float:
    return 48 + max((text_width(name, 11) for _, name in styles.values()), default=0)
