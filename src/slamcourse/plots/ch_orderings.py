"""Chapter ``orderings``: the fill-in of the same graph under different elimination orders."""

from __future__ import annotations

from collections.abc import Sequence

from slamcourse.plots.canvas import INK, legend_box
from slamcourse.plots.matrix import matrix_panel
from slamcourse.plots.picture import Figure, Picture, answer, given
from slamcourse.plots.sparsity import information_sparsity
from slamcourse.plots.svg import document, text
from slamcourse.slam import orderings as so

STYLES = {"nonzero": ("#1f4e79", "non-zero of Ω"), "fill": ("#e07b39", "fill-in")}


def fill_patterns(
    n: int, edges: Sequence[Sequence[int]], orders: Sequence[tuple[str, Sequence[int]]]
) -> str:
    """For each named order: the pattern of the Cholesky factor, rows and columns permuted into
    that order (variable eliminated k-th is row k), fill-in shaded apart."""
    cell = min(16.0, 200.0 / n)
    side = cell * n
    body: list[str] = []
    facts = []
    for k, (name, order) in enumerate(orders):
        pos = {v: i for i, v in enumerate(order)}
        fill = so.fill_edges(n, edges, order)
        kinds: dict[tuple[int, int], str] = {(i, i): "nonzero" for i in range(n)}
        for e in so.unique_edges(edges):
            i, j = sorted((pos[e[0]], pos[e[1]]))
            kinds[(j, i)] = "nonzero"
        for e in fill:
            i, j = sorted((pos[e[0]], pos[e[1]]))
            kinds[(j, i)] = "fill"
        x0 = 30 + k * (side + 50)
        body += matrix_panel(x0, 50, n, cell, kinds, STYLES, caption=name)
        body.append(text(x0, 50 + side + 18, f"{len(fill)} fill-in", fill=INK, font_size="11"))
        facts.append(f"{name} ({', '.join(str(v) for v in order)}): {len(fill)} fill-in entries")
    body += legend_box([(v[1], v[0], "marker:square") for v in STYLES.values()], 30, 50 + side + 30)
    width = 30 + len(orders) * (side + 50)
    desc = (
        f"The lower triangle of the Cholesky factor of a graph of {n} variables with "
        f"{len(so.unique_edges(edges))} edges, rows in elimination order, for "
        f"{len(orders)} orders: " + "; ".join(facts) + "."
    )
    return document(
        max(width, 320.0), 50 + side + 100, "Fill-in under different orders", desc, body
    )


def _chain_loop(n: int, a: int, b: int) -> list[tuple[int, int]]:
    return [(k, k + 1) for k in range(n - 1)] + [(a, b)]


def _lesson(n: int = 12, a: int = 3, b: int = 9) -> str:
    edges = _chain_loop(n, a, b)
    return fill_patterns(
        n,
        edges,
        [
            ("natural order", list(range(n))),
            (f"pose {b} first", [b, *(v for v in range(n) if v != b)]),
            ("minimum degree", so.min_degree_order(n, edges)),
        ],
    )


def _star() -> str:
    edges = [(0, k) for k in range(1, 7)]
    return fill_patterns(7, edges, [("hub first", list(range(7))), ("hub last", [*range(1, 7), 0])])


FIGURES: dict[str, Figure] = {
    "orderings/chain-loop-orders": _lesson,
    "orderings/star-orders": _star,
}

PICTURES: dict[str, Picture] = {
    "orderings/chain-loop-natural": answer(
        lambda p: information_sparsity(
            int(p["n"]), _chain_loop(int(p["n"]), int(p["a"]), int(p["b"]))
        )
    ),
    "orderings/chain-loop-first": answer(
        lambda p: information_sparsity(
            int(p["n"]),
            _chain_loop(int(p["n"]), int(p["a"]), int(p["b"])),
            order=[int(p["b"]), *(v for v in range(int(p["n"])) if v != int(p["b"]))][:-1],
        )
    ),
    # code: the lesson's numbers; the star of the first example, its fill-in not drawn
    "orderings/symbolic-fill": given(lambda p: _star()),
    "orderings/min-degree": given(
        lambda p: fill_patterns(
            5, [(0, 1), (1, 2), (2, 3), (3, 4)], [("natural order", list(range(5)))]
        )
    ),
}
