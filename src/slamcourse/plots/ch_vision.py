"""Chapter ``vision``: epipolar geometry, and how many RANSAC iterations a confidence costs."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from slamcourse.plots.canvas import (
    BLUE,
    GREEN,
    INK,
    MUTED,
    ORANGE,
    PURPLE,
    Chart,
    Labels,
    legend_box,
    marker,
)
from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.svg import document, el, fmt, num, polyline
from slamcourse.slam.vision import (
    epipolar_residual,
    essential_from_pose,
    ransac_iterations,
    rotation_y,
)

W, H = 560.0, 380.0
U, V = 0.3, 0.24  # half the width and height of an image plane at z = 1


def _page(p: Any) -> tuple[float, float]:
    """An oblique view of a 3-D point (camera 1's frame: x right, y down, z ahead) on the page."""
    x, y, z = (float(v) for v in p)
    return 110 + 130 * x + 100 * z, 330 + 130 * y - 80 * z


def epipolar_figure(t: Sequence[float], R: Sequence[Sequence[float]], X: Sequence[float]) -> str:
    """Two cameras (camera 2 sees ``R·X + t``), a point ``X``, its images x and x′ on the two
    image planes (z = 1 in each camera), the baseline, and the epipolar line E x in image 2."""
    Rm, tv, Xv = np.asarray(R, float), np.asarray(t, float), np.asarray(X, float)
    c2 = -Rm.T @ tv  # camera 2's centre in camera 1's frame

    def from2(p: np.ndarray) -> np.ndarray:
        return np.asarray(Rm.T @ (p - tv), dtype=float)

    x1 = Xv / Xv[2]
    X2 = Rm @ Xv + tv
    x2 = X2 / X2[2]
    E = essential_from_pose(tv, Rm)
    residual = epipolar_residual(E, x1, x2)
    line = E @ x1  # a u + b v + c = 0 in image 2
    labels = Labels(W, H)
    body = [el("rect", x=0.0, y=0.0, width=W, height=H, fill="#fbfbf8")]
    corners = [(-U, -V), (U, -V), (U, V), (-U, V)]
    for name, to_world in (("image 1", lambda p: p), ("image 2", from2)):
        pts = [_page(to_world(np.array([u, v, 1.0]))) for u, v in corners]
        body.append(
            el(
                "polygon",
                points=" ".join(f"{fmt(a)},{fmt(b)}" for a, b in pts),
                fill="#eef3f8",
                stroke=MUTED,
            )
        )
        labels.add(pts[3][0], pts[3][1], name, colour=MUTED, prefer=("s", "sw", "se"))
    o1, o2, px = _page((0, 0, 0)), _page(c2), _page(Xv)
    body.append(
        el(
            "polygon",
            points=f"{fmt(o1[0])},{fmt(o1[1])} {fmt(o2[0])},{fmt(o2[1])} {fmt(px[0])},{fmt(px[1])}",
            fill=PURPLE,
            fill_opacity="0.08",
        )
    )
    for a, b, colour, dash in ((o1, px, BLUE, None), (o2, px, ORANGE, None), (o1, o2, INK, "6 4")):
        body.append(polyline([a, b], stroke=colour, stroke_width=1.5, stroke_dasharray=dash))
        labels.block_segment(a, b)
    a, b, c = line
    ends = []
    for u in (-U, U):
        if abs(b) > 1e-12:
            v = -(a * u + c) / b
            if -V <= v <= V:
                ends.append((u, v))
    for v in (-V, V):
        if abs(a) > 1e-12:
            u = -(b * v + c) / a
            if -U <= u <= U:
                ends.append((u, v))
    if len(ends) >= 2:
        e0, e1 = (_page(from2(np.array([u, v, 1.0]))) for u, v in ends[:2])
        body.append(polyline([e0, e1], stroke=GREEN, stroke_width=2.5))
        labels.block_segment(e0, e1)
        labels.add(e1[0], e1[1], "epipolar line E x", colour=GREEN)
    p1, p2 = _page(x1), _page(from2(x2))
    for p, _name, colour in (
        (o1, "camera 1", INK),
        (o2, "camera 2", INK),
        (px, "X", PURPLE),
        (p1, "x", BLUE),
        (p2, "x′", ORANGE),
    ):
        body.append(marker(p[0], p[1], "circle", colour, 4.0))
        labels.block(p[0], p[1], 5)
    for p, name, colour in (
        (px, "point X", PURPLE),
        (p1, "x", BLUE),
        (p2, "x′", ORANGE),
        (o1, "camera 1", INK),
        (o2, "camera 2", INK),
    ):
        labels.add(p[0], p[1], name, colour=colour, bold=name in ("x", "x′"))
    labels.add((o1[0] + o2[0]) / 2, (o1[1] + o2[1]) / 2, "baseline t", colour=INK)
    legend = legend_box(
        [
            ("ray of camera 1", BLUE, ""),
            ("ray of camera 2", ORANGE, ""),
            ("epipolar line in image 2", GREEN, ""),
        ],
        10,
        10,
        labels,
    )
    desc = (
        f"Camera 1 at the origin and camera 2, {num(float(np.linalg.norm(tv)))} m away along "
        "the baseline, both see the point X. Its images x and x′ lie where the rays cross the "
        "image planes; the two rays and the baseline span one plane, the epipolar plane. That "
        "plane cuts image 2 along the epipolar line E x, and x′ lies on it: the residual "
        f"x′ᵀ E x is {num(residual)} (zero up to rounding)."
    )
    return document(W, H, "Epipolar geometry", desc, [*body, *legend, *labels.body])


def ransac_chart(sample_sizes: Sequence[int], confidence: float, mark: float | None = None) -> str:
    """Iterations RANSAC needs, against the inlier ratio, for each sample size (log scale)."""
    ratios = [0.3 + 0.65 * k / 100 for k in range(101)]
    worst = ransac_iterations(0.3, max(sample_sizes), confidence)
    chart = Chart(
        (0.3, 0.95),
        (1.0, 10 ** math.ceil(math.log10(worst))),
        log_y=True,
        x_label="inlier ratio w",
        y_label="iterations N",
    )
    legend = []
    dashes = ("", "6 4", "2 3")
    facts = []
    for k, s in enumerate(sample_sizes):
        pts = [(w, float(ransac_iterations(w, s, confidence))) for w in ratios]
        chart.line(pts, colour=(BLUE, ORANGE, GREEN)[k % 3], dash=dashes[k % 3] or None)
        legend.append((f"sample of {s}", (BLUE, ORANGE, GREEN)[k % 3], dashes[k % 3]))
        facts.append(
            f"with samples of {s}, {ransac_iterations(0.6, s, confidence)} iterations "
            f"at w = 0.6 and {ransac_iterations(0.9, s, confidence)} at w = 0.9"
        )
    if mark is not None:
        chart.line([(mark, 1.0), (mark, chart.y1)], colour=MUTED, dash="2 3")
    desc = (
        f"Iterations needed for a {num(100 * confidence)}% chance that at least one sample is "
        f"all inliers, N = ⌈log(1 − p) / log(1 − wˢ)⌉, on a log scale: "
        + "; ".join(facts)
        + ". Fewer outliers or smaller samples cut the work by orders of magnitude."
    )
    return chart.svg("How many RANSAC iterations", desc, legend)


def ransac_lines(
    points: Sequence[Sequence[float]], samples: Sequence[Sequence[int]], threshold: float
) -> str:
    """Points and the line through each candidate sample of two, with its ± threshold band."""
    from slamcourse.plots.canvas import Plane

    plane = Plane([(float(x), float(y)) for x, y in points], width=460, height=360, pad=50)
    colours = (BLUE, ORANGE, GREEN, PURPLE)
    for k, (i, j) in enumerate(samples):
        (xa, ya), (xb, yb) = points[i], points[j]
        dx, dy = float(xb) - float(xa), float(yb) - float(ya)
        norm = math.hypot(dx, dy) or 1.0
        ux, uy = dx / norm, dy / norm
        reach = 2 * max(plane.x1 - plane.x0, plane.y1 - plane.y0) + 1
        a = (float(xa) - reach * ux, float(ya) - reach * uy)
        b = (float(xa) + reach * ux, float(ya) + reach * uy)
        colour = colours[k % 4]
        for off in (-threshold, threshold):
            plane.body.append(
                polyline(
                    [
                        plane.px(a[0] - off * uy, a[1] + off * ux),
                        plane.px(b[0] - off * uy, b[1] + off * ux),
                    ],
                    stroke=colour,
                    stroke_width=0.8,
                    stroke_dasharray="2 3",
                )
            )
        plane.body.append(
            polyline(
                [plane.px(*a), plane.px(*b)],
                stroke=colour,
                stroke_width=1.5,
                stroke_dasharray=("", "6 4", "9 3 2 3", "2 2")[k % 4] or None,
            )
        )
    for k, (x, y) in enumerate(points):
        plane.point(float(x), float(y), colour=INK, shape="circle", size=4, label=f"{k}")
    pairs = "; ".join(f"candidate {k}: points {i} and {j}" for k, (i, j) in enumerate(samples))
    desc = (
        f"{len(points)} points and {len(samples)} candidate lines, each through one sample of "
        f"two points ({pairs}), "
        f"with a band of ± {num(threshold)} around it: the points inside a band are that "
        "candidate's inliers."
    )
    legend = [
        (f"candidate {k}", colours[k % 4], ("", "6 4", "9 3 2 3", "2 2")[k % 4])
        for k in range(len(samples))
    ]
    return plane.svg("RANSAC candidates and their inlier bands", desc, legend)


_R = rotation_y(0.25)
_T = (-1.0, 0.0, 0.15)
_X = (0.35, -0.2, 2.6)

FIGURES: dict[str, Figure] = {
    "vision/epipolar-geometry": lambda: epipolar_figure(_T, _R.tolist(), _X),
    "vision/ransac-iterations-chart": lambda: ransac_chart([5, 8], 0.99),
}

PICTURES: dict[str, Picture] = {
    "vision/epipolar-residual": given(lambda p: epipolar_figure(_T, _R.tolist(), _X)),
    "vision/essential-from-pose": given(lambda p: epipolar_figure(_T, _R.tolist(), _X)),
    "vision/ransac-iterations": given(lambda p: ransac_chart([5, 8], 0.99)),
    "vision/ransac-fix": given(
        lambda p: ransac_lines(
            [[0, 0], [1, 1], [2, 2], [3, 3], [4, 4], [0, 4], [4, 0]], [[5, 6], [0, 1], [1, 5]], 0.5
        )
    ),
}
