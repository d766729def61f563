"""Chapter ``pose-graph``: one edge's error in frames, and a small graph before and after
Gauss-Newton."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, MUTED, ORANGE, PURPLE, Plane
from slamcourse.plots.picture import Figure, Params, Picture, given
from slamcourse.plots.svg import num
from slamcourse.slam.posegraph import Edge, edge_error, gauss_newton, simulate
from slamcourse.slam.se2 import compose


def _pt(p: Any) -> str:
    return f"({num(p[0])}, {num(p[1])}, {num(p[2])})"


def edge_figure(
    xi: Sequence[float], xj: Sequence[float], z: Sequence[float], *, show_results: bool = True
) -> str:
    """Poses x_i and x_j, the measurement z drawn from x_i (where it says x_j should be,
    x_i ⊕ z), and the error e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j) ("?" while asked)."""
    xi, xj, z = ([float(v) for v in p] for p in (xi, xj, z))
    pred = list(compose(xi, z))
    e = edge_error(xi, xj, z)
    pts = [
        (p[0] + dx, p[1] + dy) for p in (xi, xj, pred) for dx in (-0.5, 0.5) for dy in (-0.5, 0.5)
    ]
    plane = Plane(pts, width=480, height=380, pad=30, grid=0.5)
    plane.segment((xi[0], xi[1]), (pred[0], pred[1]), colour=ORANGE, dash="6 4", arrow=True)
    plane.segment((pred[0], pred[1]), (xj[0], xj[1]), colour=PURPLE, width=2.0)
    plane.pose(*xi, colour=BLUE, axes=0.4, label=f"x_i = {_pt(xi)}")
    plane.pose(*xj, colour=GREEN, label=f"x_j = {_pt(xj)}")
    plane.pose(*pred, colour=ORANGE, hollow=True, label="x_i ⊕ z: where z puts x_j")
    text = f"e = {_pt(e)}" if show_results else "e = ?"
    plane.label((pred[0] + xj[0]) / 2, (pred[1] + xj[1]) / 2, text, colour=PURPLE, bold=True)
    desc = (
        f"Pose x_i = {_pt(xi)} and pose x_j = {_pt(xj)}. The edge's measurement z = {_pt(z)}, "
        f"applied in x_i's frame, says x_j should be at x_i ⊕ z = {_pt(pred)} (hollow). The "
        "error is the gap between that and x_j, written in the predicted pose's frame: "
        + (f"e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j) = {_pt(e)}." if show_results else "it is asked.")
    )
    return plane.svg("The error of one pose-graph edge", desc)


def graph_before_after(poses: np.ndarray, edges: Sequence[Edge], iterations: int = 10) -> str:
    """The initial guess and the Gauss-Newton estimate of a pose graph, with its edges."""
    after, history = gauss_newton(poses, edges, iterations)
    plane = Plane(
        [(float(x), float(y)) for x, y, _ in np.vstack([poses, after])],
        width=540,
        height=400,
        pad=30,
    )
    n = len(poses)
    for est, colour, dash in ((poses, ORANGE, "6 4"), (after, BLUE, None)):
        plane.path([(float(x), float(y)) for x, y, _ in est], colour=colour, dash=dash, width=1.8)
        for e in edges:
            if abs(e.i - e.j) != 1:
                a, b = est[e.i], est[e.j]
                plane.segment(
                    (float(a[0]), float(a[1])),
                    (float(b[0]), float(b[1])),
                    colour=colour,
                    dash="1 3",
                    width=1.0,
                )
    for k, (x, y, th) in enumerate(after):
        plane.pose(
            float(x),
            float(y),
            float(th),
            colour=BLUE,
            size=8,
            label="pose 0 (fixed)" if k == 0 else None,
        )
    loops = sum(1 for e in edges if abs(e.i - e.j) != 1)
    desc = (
        f"A pose graph of {n} poses, {n - 1} odometry edges and {loops} loop closures (dotted). "
        f"The initial guess, dead reckoning (dashed), has χ² = {num(history[0])}; after "
        f"{iterations} Gauss-Newton steps with pose 0 held fixed, χ² = {num(history[-1])}."
    )
    legend = [
        ("initial guess", ORANGE, "6 4"),
        ("after Gauss-Newton", BLUE, ""),
        ("loop closures", MUTED, "1 3"),
    ]
    return plane.svg("A pose graph before and after Gauss-Newton", desc, legend)


def _small() -> tuple[np.ndarray, tuple[Edge, ...]]:
    return simulate(seed=7, n=14, loops=3, noise=(0.08, 0.05))


def _initial_only() -> str:
    poses, edges = _small()
    return graph_before_after(poses, edges, iterations=0)


def _error_picture(p: Params, shown: bool) -> str:
    return edge_figure(
        [p["xi"], p["yi"], p["ti"]],
        [p["xj"], p["yj"], p["tj"]],
        [p["zx"], p["zy"], p["zt"]],
        show_results=shown,
    )


FIGURES: dict[str, Figure] = {
    "pose-graph/edge-error-frames": lambda: edge_figure(
        [0.5, 0.5, 0.3], [2.3, 1.6, 1.0], [1.6, 0.4, 0.5]
    ),
    "pose-graph/before-after": lambda: graph_before_after(*_small()),
}

PICTURES: dict[str, Picture] = {
    "pose-graph/error-value": Picture(_error_picture),
    "pose-graph/edge-error": given(
        lambda p: edge_figure([1, 2, 0.5], [1.9, 2.6, 1.1], [1, 0, 0.5], show_results=False)
    ),
    "pose-graph/edge-jacobians": given(
        lambda p: edge_figure([0, 0, 0], [1, 0.2, 0.1], [1, 0, 0], show_results=False)
    ),
    "pose-graph/gauss-newton": given(lambda p: _initial_only()),
}
