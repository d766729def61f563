"""Chapter ``graph``: a pose graph beside its information matrix Ω (sparsity and values)."""

from __future__ import annotations

import math
from collections.abc import Sequence

from slamcourse.plots.canvas import BLUE, INK, ORANGE, Labels, legend_box
from slamcourse.plots.matrix import matrix_panel
from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.sparsity import information_sparsity
from slamcourse.plots.svg import document, el, polyline, text

STYLES = {
    "diag": ("#1f4e79", "diagonal (every pose)"),
    "odometry": ("#9cc3e6", "odometry edge"),
    "loop": ("#b3541e", "loop closure"),
}


def _layout(n: int) -> list[tuple[float, float]]:
    """Poses along a U-turn (px, in a 220 × 200 box), so that a loop can close across it."""
    if n == 1:
        return [(110.0, 100.0)]
    out = []
    for k in range(n):
        a = math.pi * k / (n - 1)
        out.append((110 - 85 * math.cos(a), 110 - 80 * math.sin(a)))
    return out


def graph_and_omega(
    n: int,
    edges: Sequence[tuple[int, int]],
    *,
    values: Sequence[Sequence[float]] | None = None,
    title: str = "A pose graph and the sparsity of its information matrix",
) -> str:
    """Poses as numbered circles linked by their edges (an edge between non-neighbours is a
    loop closure, drawn dashed), and Ω's non-zero entries (``values``: written in the cells)."""
    pos = _layout(n)
    labels = Labels(640, 300)
    body: list[str] = []
    kinds: dict[tuple[int, int], str] = {(i, i): "diag" for i in range(n)}
    loops = 0
    for i, j in edges:
        loop = abs(i - j) != 1
        loops += loop
        kinds[(i, j)] = kinds[(j, i)] = "loop" if loop else "odometry"
        (x0, y0), (x1, y1) = pos[i], pos[j]
        body.append(
            polyline(
                [(20 + x0, 40 + y0), (20 + x1, 40 + y1)],
                stroke=ORANGE if loop else INK,
                stroke_width=2.0,
                stroke_dasharray="6 4" if loop else None,
            )
        )
    for k, (x, y) in enumerate(pos):
        body.append(
            el("circle", cx=20 + x, cy=40 + y, r=12.0, fill="#fff", stroke=BLUE, stroke_width=2.0)
        )
        body.append(
            text(20 + x, 40 + y + 4, f"x{k}", text_anchor="middle", fill=INK, font_size="10")
        )
    body.append(text(20, 24, "pose graph", fill=INK, font_weight="bold"))
    cell = min(26.0, 200.0 / n)
    x0 = 300.0
    body += matrix_panel(
        x0, 56, n, cell, kinds, STYLES, values=values, caption="Ω (one cell per pose)"
    )
    used = [k for k in STYLES if k in kinds.values()]
    body += legend_box(
        [(STYLES[k][1], STYLES[k][0], "marker:square") for k in used], 20, 250, labels
    )
    nonzero = len(kinds)
    desc = (
        f"{n} poses linked by {len(edges) - loops} odometry edges"
        + (f" and {loops} loop closure{'s' if loops != 1 else ''}" if loops else "")
        + f". Ω has a non-zero on its diagonal for every pose and a symmetric pair of "
        f"non-zeros for every linked pair: {nonzero} of its {n * n} entries are non-zero."
        + (" The values are written in the cells." if values is not None else "")
    )
    height = max(56 + n * cell + 20, 320.0)
    return document(x0 + n * cell + 30, height, title, desc, body)


def _solve_picture() -> str:
    omega = [[12.0, -1.0, -1.0], [-1.0, 2.0, -1.0], [-1.0, -1.0, 2.0]]
    return graph_and_omega(
        3, [(0, 1), (1, 2), (0, 2)], values=omega, title="The information matrix Ω of three poses"
    )


def _chain_loop() -> str:
    n = 8
    edges = [(k, k + 1) for k in range(n - 1)] + [(0, n - 1)]
    return graph_and_omega(n, edges)


_BUILD = [(0, 1, 1.0), (1, 2, 1.0), (2, 3, 1.0), (3, 0, 2.0)]

FIGURES: dict[str, Figure] = {
    "graph/chain-and-loop": _chain_loop,
    # the loop closure's elimination fills the rows between its two ends
    "graph/cholesky-fill": lambda: information_sparsity(
        8, [(k, k + 1) for k in range(7)] + [(0, 7)]
    ),
}

PICTURES: dict[str, Picture] = {
    # code: the lesson's numbers (a square loop written from the newer pose back)
    "graph/build-omega": given(lambda p: graph_and_omega(4, [(i, j) for i, j, _ in _BUILD])),
    "graph/solve-information": given(lambda p: _solve_picture()),
}
