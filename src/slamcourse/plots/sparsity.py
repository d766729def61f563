"""The sparsity pattern of an information matrix Ω, before and after eliminating variables.

Ω (n × n, one block per pose or variable) has a non-zero at (i, i) for every variable and at
(i, j) and (j, i) for every constraint between i and j. Eliminating a variable (a Schur
complement) links all its remaining neighbours to each other: the new non-zeros are *fill-in*.
"""

from __future__ import annotations

from collections.abc import Sequence

from slamcourse.plots.svg import document, el, fmt, text

CELL_MAX = 22.0
PANEL = 240.0
MAX_N = 30


def pattern(n: int, edges: Sequence[Sequence[int]]) -> set[tuple[int, int]]:
    """Non-zero cells (row, col) of Ω for ``n`` variables and the constraints ``edges``."""
    cells = {(i, i) for i in range(n)}
    for e in edges:
        i, j = int(e[0]), int(e[1])
        cells |= {(i, j), (j, i)}
    return cells


def eliminate(
    n: int, edges: Sequence[Sequence[int]], order: Sequence[int]
) -> tuple[set[tuple[int, int]], set[tuple[int, int]]]:
    """(all non-zeros of the filled matrix, the fill-in among them) after eliminating ``order``."""
    nbrs: dict[int, set[int]] = {i: set() for i in range(n)}
    for e in edges:
        i, j = int(e[0]), int(e[1])
        if i != j:
            nbrs[i].add(j)
            nbrs[j].add(i)
    before = pattern(n, edges)
    filled = set(before)
    done: set[int] = set()
    for v in order:
        live = sorted(nbrs[v] - done)
        for a in live:
            for b in live:
                if a != b and (a, b) not in filled:
                    filled.add((a, b))
                    nbrs[a].add(b)
        done.add(v)
    return filled, filled - before


def _panel(
    x0: float,
    y0: float,
    n: int,
    cells: set[tuple[int, int]],
    fill: set[tuple[int, int]],
    label: str,
) -> list[str]:
    size = min(CELL_MAX, PANEL / max(n, 1))
    out = [text(x0, y0 - 8, label, fill="#222", font_weight="bold")]
    out.append(el("rect", x=x0, y=y0, width=size * n, height=size * n, fill="#fff", stroke="#888"))
    out.extend(cell_marks(cells, fill, x0, y0, size))
    return out


def cell_marks(
    cells: set[tuple[int, int]], fill: set[tuple[int, int]], x0: float, y0: float, size: float
) -> list[str]:
    """The nonzero cells of a matrix pattern at ``(x0, y0)``, ``size`` per cell: a filled
    square each, fill-in (``fill``) a crossed light square, so it never relies on colour."""
    out = []
    for i, j in sorted(cells):
        x, y = x0 + j * size, y0 + i * size
        if (i, j) in fill:
            out.append(
                el(
                    "rect",
                    x=x + 1,
                    y=y + 1,
                    width=size - 2,
                    height=size - 2,
                    fill="#f3d9c4",
                    stroke="#b3541e",
                )
            )
            out.append(
                el(
                    "path",
                    d=f"M{fmt(x + 3)},{fmt(y + 3)}L{fmt(x + size - 3)},"
                    f"{fmt(y + size - 3)}M{fmt(x + size - 3)},{fmt(y + 3)}L{fmt(x + 3)},"
                    f"{fmt(y + size - 3)}",
                    stroke="#b3541e",
                    stroke_width=1.5,
                )
            )
        else:
            out.append(
                el("rect", x=x + 1, y=y + 1, width=size - 2, height=size - 2, fill="#1f4e79")
            )
    return out


def information_sparsity(
    n: int,
    edges: Sequence[Sequence[int]],
    order: Sequence[int] | None = None,
    *,
    of_total: int | None = None,
) -> str:
    """Ω's non-zeros before and after eliminating ``order`` (default: every variable but the
    last, in index order), with fill-in drawn as crossed cells. ``of_total``: the real number of
    variables when only the first ``n`` are drawn."""
    n = int(n)
    if n > MAX_N:
        raise ValueError(f"draw at most {MAX_N} variables (got {n}); pass of_total instead")
    order = list(range(n - 1)) if order is None else [int(v) for v in order]
    before = pattern(n, edges)
    filled, fill = eliminate(n, edges, order)
    size = min(CELL_MAX, PANEL / max(n, 1))
    side = size * n
    w, h = 2 * side + 100, side + 90
    body = _panel(30, 40, n, before, set(), "Ω before")
    body += _panel(70 + side, 40, n, filled, fill, "after elimination")
    ly = 40 + side + 24
    body += [
        el("rect", x=30.0, y=ly - 10, width=12.0, height=12.0, fill="#1f4e79"),
        text(48, ly, "non-zero", fill="#222"),
        el("rect", x=130.0, y=ly - 10, width=12.0, height=12.0, fill="#f3d9c4", stroke="#b3541e"),
        text(148, ly, f"fill-in (×): {len(fill)} new non-zeros", fill="#222"),
    ]
    shown = f"the first {n} of {of_total}" if of_total and of_total > n else f"{n}"
    desc = (
        f"Information matrix of {shown} variables with {len(list(edges))} constraints: "
        f"{len(before)} non-zero entries out of {n * n}. Eliminating variables in the order "
        f"{', '.join(str(v) for v in order) or '(none)'} leaves {len(filled)} non-zeros, of which "
        f"{len(fill)} are fill-in."
    )
    return document(
        w, h, "Sparsity of the information matrix before and after elimination", desc, body
    )
