"""Chapter ``scan-matching``: ICP iterations bringing a scan onto a model, and a beam through a
grid (Bresenham's cells)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, PURPLE, Plane, legend_box
from slamcourse.plots.picture import Figure, Picture, answer, given
from slamcourse.plots.svg import document, el, num, polyline, text
from slamcourse.slam.raycast import bresenham
from slamcourse.slam.scanmatch import icp_step, rotation, sum_squared_error


def model_and_scan() -> tuple[np.ndarray, np.ndarray]:
    """The chapter's corridor corner: model points Q on two walls, and the scan P, the same
    corner seen from a pose 0.2 rad and (−0.4, 0.3) m off (every third point)."""
    wall_a = [(x, 0.0) for x in np.linspace(0, 4, 17)]
    wall_b = [(4.0, y) for y in np.linspace(0.5, 3, 11)]
    q = np.array(wall_a + wall_b)
    p = (rotation(-0.2) @ (q[::3] - np.array([-0.4, 0.3])).T).T
    return p, q


def icp_figure(p: np.ndarray, q: np.ndarray, iterations: int = 4) -> str:
    """P, moved by each of ``iterations`` ICP steps, on top of the model Q; the sum of squared
    distances to the paired points after each step."""
    pts = [tuple(v) for v in np.vstack([p, q])]
    plane = Plane(pts, width=520, height=400, pad=36)
    for x, y in q:
        plane.point(float(x), float(y), colour=INK, shape="square", size=4)
    current = p.copy()
    colours = (ORANGE, PURPLE, BLUE, GREEN, GREEN)
    errors = []
    legend = [("model Q", INK, "marker:square")]
    for k in range(iterations + 1):
        shape = "circle" if k in (0, iterations) else "ring"
        colour = colours[min(k, len(colours) - 1)]
        for x, y in current:
            plane.point(float(x), float(y), colour=colour, shape=shape, size=4)
        name = "scan P" if k == 0 else f"after step {k}"
        if k in (0, 1, 2, iterations):
            legend.append((name, colour, f"marker:{shape}"))
        if k == iterations:
            break
        theta, t, pairs = icp_step(current, q)
        if k == 0:
            for i, j in enumerate(pairs):
                plane.segment(tuple(current[i]), tuple(q[j]), colour=MUTED, dash="2 2", width=0.8)
        current = (rotation(theta) @ current.T).T + t
        errors.append(
            float(sum_squared_error(current, q[icp_step(current, q)[2]], 0.0, np.zeros(2)))
        )
    desc = (
        f"A scan P of {len(p)} points of a corridor corner and the model Q of {len(q)} points. "
        "Each ICP step pairs every scan point with its nearest model point (the first pairing "
        "is drawn dotted) and moves the scan by the rigid motion that best aligns the pairs. "
        "After each step the sum of squared distances to the nearest model points is "
        + ", ".join(num(e) for e in errors)
        + " m²: the first pairings are partly wrong, so it takes a few steps to settle, and it "
        "settles where the nearest-point pairs stop changing, not necessarily at zero."
    )
    return plane.svg("ICP iterations", desc, legend)


def beam_figure(x0: int, y0: int, x1: int, y1: int, *, show_results: bool = True) -> str:
    """A grid with the beam from cell (x0, y0) to (x1, y1) and the cells Bresenham's line
    visits (free cells, then the hit cell)."""
    cells = bresenham(x0, y0, x1, y1)
    xs = [c[0] for c in cells] + [x0, x1]
    ys = [c[1] for c in cells] + [y0, y1]
    cx0, cx1, cy0, cy1 = min(xs) - 1, max(xs) + 1, min(ys) - 1, max(ys) + 1
    cols, rows = cx1 - cx0 + 1, cy1 - cy0 + 1
    size = min(32.0, 480.0 / cols, 300.0 / rows)
    left, top = 30.0, 30.0

    def px(cx: float, cy: float) -> tuple[float, float]:
        return left + (cx - cx0 + 0.5) * size, top + (cy1 - cy + 0.5) * size

    body = []
    for c in range(cx0, cx1 + 1):
        for r in range(cy0, cy1 + 1):
            x, y = px(c, r)
            if not show_results:
                fill = "#fff"
            elif (c, r) == cells[-1]:
                fill = "#333"
            elif (c, r) in cells:
                fill = "#cfe3f3"
            else:
                fill = "#fff"
            body.append(
                el(
                    "rect",
                    x=x - size / 2,
                    y=y - size / 2,
                    width=size,
                    height=size,
                    fill=fill,
                    stroke="#bbb",
                )
            )
    body.append(polyline([px(x0, y0), px(x1, y1)], stroke=ORANGE, stroke_width=2.0))
    a, b = px(x0, y0), px(x1, y1)
    body.append(el("circle", cx=a[0], cy=a[1], r=5.0, fill=BLUE))
    body.append(el("circle", cx=b[0], cy=b[1], r=5.0, fill=ORANGE))
    height = top + rows * size + 50
    body += legend_box(
        [("sensor cell", BLUE, "marker:circle"), ("beam", ORANGE, "")]
        + (
            [
                ("crossed (free)", "#cfe3f3", "marker:square"),
                ("hit (occupied)", "#333", "marker:square"),
            ]
            if show_results
            else []
        ),
        left + cols * size + 12,
        top,
    )
    body.append(
        text(
            left,
            height - 14,
            f"from cell ({x0}, {y0}) to cell ({x1}, {y1}); x to the right, y up",
            fill=MUTED,
            font_size="11",
        )
    )
    desc = f"A beam from cell ({x0}, {y0}) to cell ({x1}, {y1}) on a grid. " + (
        f"Bresenham's line visits {len(cells)} cells, max(|Δx|, |Δy|) + 1: "
        f"{len(cells) - 1} crossed cells, marked free, and the hit cell, marked occupied."
        if show_results
        else "Which cells it crosses is asked."
    )
    return document(left + cols * size + 180, height, "A beam through a grid", desc, body)


def _points(p: Sequence[Sequence[float]]) -> np.ndarray:
    return np.asarray(p, dtype=float)


_P, _Q = model_and_scan()


def _xy(v: Sequence[float]) -> tuple[float, float]:
    return float(v[0]), float(v[1])


def two_points(
    p1: Sequence[float], p2: Sequence[float], q1: Sequence[float], q2: Sequence[float]
) -> str:
    """Two points of a scan and their matches in the model: the segments' directions differ by
    the rotation, whatever the translation."""
    plane = Plane([_xy(v) for v in (p1, p2, q1, q2)], width=440, height=380, pad=40, grid=1.0)
    plane.segment(_xy(p1), _xy(p2), colour=ORANGE, arrow=True)
    plane.segment(_xy(q1), _xy(q2), colour=BLUE, arrow=True)
    for v, name, colour in (
        (p1, "p1", ORANGE),
        (p2, "p2", ORANGE),
        (q1, "q1", BLUE),
        (q2, "q2", BLUE),
    ):
        plane.point(float(v[0]), float(v[1]), colour=colour, shape="circle", label=name)
    desc = (
        f"Scan points p1 = ({num(p1[0])}, {num(p1[1])}) and p2 = ({num(p2[0])}, {num(p2[1])}) "
        f"and their matches q1 = ({num(q1[0])}, {num(q1[1])}) and q2 = ({num(q2[0])}, "
        f"{num(q2[1])}) m. The arrow p1 → p2 turns into the arrow q1 → q2 by the rotation "
        "alone: the translation moves both ends alike."
    )
    return plane.svg("Two matched points", desc, [("scan", ORANGE, ""), ("model", BLUE, "")])


FIGURES: dict[str, Figure] = {
    "scan-matching/icp-iterations": lambda: icp_figure(_P, _Q),
    "scan-matching/beam-through-grid": lambda: beam_figure(1, 1, 11, 5),
}

PICTURES: dict[str, Picture] = {
    "scan-matching/two-point-angle": given(
        lambda p: two_points(
            (p["p1x"], p["p1y"]), (p["p2x"], p["p2y"]), (p["q1x"], p["q1y"]), (p["q2x"], p["q2y"])
        )
    ),
    "scan-matching/icp-step": given(
        lambda p: icp_figure(
            _points([[4.9, 0.1], [-0.1, 0.1], [-0.1, 3.1]]),
            _points([[0, 0], [5, 0], [0, 3]]),
            iterations=1,
        )
    ),
    "scan-matching/align-2d": given(lambda p: icp_figure(_P, _Q, iterations=1)),
    "scan-matching/beam-cells": answer(
        lambda p: beam_figure(int(p["x0"]), int(p["y0"]), int(p["x1"]), int(p["y1"]))
    ),
    "scan-matching/bresenham": given(lambda p: beam_figure(0, 0, 7, 3, show_results=False)),
    "scan-matching/beam-update": given(lambda p: beam_figure(4, 1, 0, 0, show_results=False)),
}
