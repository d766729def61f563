"""Chapter ``se3``: the accuracy of rotation logarithms, and sphere2500 before and after.

Prose figures (no arguments, drawn from :mod:`slamcourse.slam.se3` and the shipped data):

- ``se3/log-accuracy``: the error of three ways to take the logarithm of a rotation, against
  its angle, on a log scale: ``acos`` of the trace with ``θ/(2 sin θ)``, the same with
  ``atan2``, and the robust method (series near 0, symmetric part near π);
- ``se3/sphere``: sphere2500's positions seen from above, composed odometry against the
  Gauss-Newton optimum and the ground truth.

Exercise pictures: ``se3/so3-log`` (the three regimes of the logarithm, givens only) and
``se3/optimise-3d`` (a window of sphere2500 as its odometry composes it, before optimising).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import numpy as np

from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.svg import document, el, fmt, num, polyline, text
from slamcourse.slam import se3

W, H = 560.0, 320.0
LEFT, RIGHT, TOP, BOTTOM = 64.0, 150.0, 36.0, 46.0
ANGLES = 60


def _data(name: str) -> str:
    from slamcourse.course.locate import bundled_course_root

    path = bundled_course_root() / "exercises" / "se3" / "data" / name
    return path.read_text(encoding="utf-8")


def _naive_log(r: np.ndarray, use_atan2: bool) -> np.ndarray:
    """``θ/(2 sin θ) (R − Rᵀ)ˇ`` with θ from ``acos`` of the trace (or ``atan2``)."""
    v = se3.vee(r)
    c = (float(np.trace(r)) - 1) / 2
    s = float(np.linalg.norm(v))
    theta = math.atan2(s, c) if use_atan2 else math.acos(max(-1.0, min(1.0, c)))
    if theta == 0 or math.sin(theta) == 0:
        return np.zeros(3)
    out: np.ndarray = theta / math.sin(theta) * v
    return out


@lru_cache(maxsize=1)
def log_errors() -> tuple[list[float], dict[str, list[float]]]:
    """Angles ``π·10^(−u)`` … and the worst error (rad) of each method over 40 axes, at angles
    from 1e-9 to π − 1e-9 (the log of ``Exp(θ n)`` against ``θ n``)."""
    small = [10.0**u for u in np.linspace(-9, -0.5, ANGLES // 2)]
    near = [math.pi - 10.0**u for u in np.linspace(-0.6, -9, ANGLES // 2)]
    angles = small + near
    rng = np.random.default_rng(22)
    axes = rng.normal(size=(40, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    errors: dict[str, list[float]] = {"acos": [], "atan2": [], "robust": []}
    for theta in angles:
        worst = {k: 0.0 for k in errors}
        for n in axes:
            w = theta * n
            r = se3.so3_exp(w)
            for key, got in (
                ("acos", _naive_log(r, False)),
                ("atan2", _naive_log(r, True)),
                ("robust", se3.so3_log(r)),
            ):
                worst[key] = max(worst[key], float(np.max(np.abs(got - w))))
        for key in errors:
            errors[key].append(worst[key])
    return angles, errors


def log_accuracy() -> str:
    angles, errors = log_errors()
    floor = 1e-17
    x0, x1 = LEFT, W - RIGHT
    y0, y1 = TOP, H - BOTTOM
    half = (x1 - x0) / 2

    def px(k: int) -> float:
        return x0 + (x1 - x0) * k / (len(angles) - 1)

    def py(err: float) -> float:
        lg = min(math.log10(max(err, floor)), 1.0)  # errors above 10 rad drawn at the top
        return y1 - (y1 - y0) * (lg + 17) / 18

    body = [el("rect", x=x0, y=y0, width=x1 - x0, height=y1 - y0, fill="#fff", stroke="#999")]
    for lg in (-15, -12, -9, -6, -3, 0):  # the top edge is 10 rad
        y = py(10.0**lg)
        body.append(el("line", x1=x0, y1=y, x2=x1, y2=y, stroke="#eee"))
        body.append(text(x0 - 6, y + 4, f"1e{lg}", text_anchor="end", fill="#333"))
    body.append(el("line", x1=x0 + half, y1=y0, x2=x0 + half, y2=y1, stroke="#999"))
    body.append(text(x0 + half / 2, y1 + 18, "θ from 1e-9 to 0.3 rad", text_anchor="middle"))
    body.append(text(x0 + 1.5 * half, y1 + 18, "π − θ from 0.25 to 1e-9", text_anchor="middle"))
    body.append(
        text(x0 + (x1 - x0) / 2, y1 + 36, "angle (log scale on each side)", text_anchor="middle")
    )
    body.append(text(14, TOP - 12, "worst error of Log(Exp(θ n)) over 40 axes (rad)", fill="#333"))
    styles = {
        "acos": ("#b2182b", "6 3", "acos of the trace, θ/(2 sin θ)"),
        "atan2": ("#2166ac", "2 2", "atan2, θ/(2 sin θ)"),
        "robust": ("#1b7837", "", "series near 0, symmetric part near π"),
    }
    for row, (key, (colour, dash, label)) in enumerate(styles.items()):
        pts = [(px(k), py(e)) for k, e in enumerate(errors[key])]
        body.append(polyline(pts, stroke=colour, stroke_width=2, stroke_dasharray=dash or None))
        ly = TOP + 14 + 40 * row
        body.append(
            el(
                "line",
                x1=x1 + 10,
                y1=ly,
                x2=x1 + 34,
                y2=ly,
                stroke=colour,
                stroke_width=2,
                stroke_dasharray=dash or None,
            )
        )
        for part, line in enumerate(_wrap_words(label, 16)):
            body.append(text(x1 + 38, ly + 4 + 13 * part, line, font_size="11"))
    worst = {k: max(v) for k, v in errors.items()}
    desc = (
        "Worst error of three rotation logarithms against the angle, on log scales, for angles "
        f"from 1e-9 rad to pi minus 1e-9. acos of the trace: worst {num(worst['acos'], 2)} rad "
        "(exactly zero output for the tiniest angles, large errors near pi). atan2 with "
        f"theta/(2 sin theta): worst {num(worst['atan2'], 2)} rad, all of it near pi. "
        "Series near 0 "
        f"and symmetric part near pi: worst {num(worst['robust'], 2)} rad everywhere."
    )
    return document(W, H, "How accurate is the logarithm of a rotation?", desc, body)


def _wrap_words(label: str, width: int) -> list[str]:
    lines: list[str] = []
    for word in label.split():
        if lines and len(lines[-1]) + 1 + len(word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


@lru_cache(maxsize=1)
def sphere_positions() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """sphere2500 seen from pose 0: composed odometry, Gauss-Newton optimum (6 steps, converged)
    and the ground truth aligned rigidly onto the optimum (each ``(2500, 3)``)."""
    text = _data("sphere2500.txt")
    graph = se3.parse_edge3(text)
    truth = se3.parse_edge3(_data("sphere2500_groundtruth.txt"))
    x, _ = se3.optimise_text(text, 6)  # converged: the 7th step moves no pose by 1e-6 m
    optimum = se3.positions_from_first(x)
    true = se3.align(se3.positions_from_first(truth.poses), optimum)
    return se3.positions_from_first(graph.poses), optimum, true


def _panel(
    x0: float,
    y0: float,
    size: float,
    series: Sequence[tuple[np.ndarray, str, str]],
    span: tuple[float, float, float, float],
) -> list[str]:
    xmin, xmax, ymin, ymax = span
    scale = size / max(xmax - xmin, ymax - ymin)
    body = [el("rect", x=x0, y=y0, width=size, height=size, fill="#fff", stroke="#999")]
    for pts, colour, dash in series:
        step = max(1, len(pts) // 1200)
        xy = [(x0 + (p[0] - xmin) * scale, y0 + size - (p[1] - ymin) * scale) for p in pts[::step]]
        body.append(polyline(xy, stroke=colour, stroke_width=1, stroke_dasharray=dash or None))
    return body


def sphere_figure() -> str:
    odometry, optimum, true = sphere_positions()
    size = 230.0
    y0 = 44.0

    def span(*clouds: np.ndarray) -> tuple[float, float, float, float]:
        allp = np.concatenate(clouds)
        pad = 0.03 * float(np.ptp(allp[:, :2]))
        return (
            float(allp[:, 0].min()) - pad,
            float(allp[:, 0].max()) + pad,
            float(allp[:, 1].min()) - pad,
            float(allp[:, 1].max()) + pad,
        )

    ate_odometry = se3.ate_rmse(odometry, true)
    ate_optimum = se3.ate_rmse(optimum, true)
    body = _panel(20, y0, size, [(odometry, "#b2182b", "")], span(odometry))
    body += _panel(
        300, y0, size, [(true, "#999999", "4 2"), (optimum, "#1b7837", "")], span(optimum, true)
    )
    body.append(text(20, y0 - 10, "composed odometry (initial guess)", fill="#b2182b"))
    body.append(text(300, y0 - 10, "optimum (solid) on the truth (dashed)", fill="#1b7837"))
    body.append(
        text(20, y0 + size + 20, f"error after rigid alignment: {num(ate_odometry, 3)} m RMS")
    )
    body.append(
        text(300, y0 + size + 20, f"error after rigid alignment: {num(ate_optimum, 3)} m RMS")
    )
    desc = (
        "sphere2500 seen from above (x and y of every position seen from pose 0). Left: the "
        f"initial guess composed from the odometry, {num(ate_odometry, 3)} m RMS from the ground "
        "truth after the best rigid alignment, a twisted ball. Right: the Gauss-Newton optimum "
        f"after 10 steps drawn over the aligned ground truth, {num(ate_optimum, 3)} m RMS."
    )
    return document(550, y0 + size + 34, "sphere2500 before and after Gauss-Newton", desc, body)


def _so3_picture() -> str:
    """The three regimes of the logarithm (givens only: no rotation vector is shown)."""
    body = []
    x0, x1, y = 40.0, 520.0, 70.0
    body.append(el("line", x1=x0, y1=y, x2=x1, y2=y, stroke="#333", stroke_width=2))
    marks = [(0.0, "0"), (math.pi / 2, "π/2"), (math.pi, "π")]
    for angle, label in marks:
        x = x0 + (x1 - x0) * angle / math.pi
        body.append(el("line", x1=x, y1=y - 6, x2=x, y2=y + 6, stroke="#333"))
        body.append(text(x, y + 22, label, text_anchor="middle"))
    spans = [
        (0.0, 0.35, "#2166ac", "tiny: series, atan2"),
        (0.35, 2.7, "#1b7837", "θ/(2 sin θ) (R − Rᵀ)ˇ"),
        (2.7, math.pi, "#b2182b", "near π: symmetric part"),
    ]
    for a, b, colour, label in spans:
        xa, xb = x0 + (x1 - x0) * a / math.pi, x0 + (x1 - x0) * b / math.pi
        body.append(
            el("rect", x=xa, y=y - 40, width=xb - xa, height=22, fill=colour, opacity="0.25")
        )
        body.append(text((xa + xb) / 2, y - 46, label, text_anchor="middle", font_size="11"))
    body.append(
        text(x0, y + 48, "the angle θ = |w| of the rotation R; the answer w is yours to compute")
    )
    desc = (
        "The angle axis from 0 to pi split into three regimes of the rotation logarithm: tiny "
        "angles (a series and atan2), the middle (theta over 2 sin theta times the "
        "antisymmetric part), and angles near pi (the axis from the symmetric part)."
    )
    return document(560, 130, "Three regimes of the rotation logarithm", desc, body)


def _window_picture() -> str:
    """A 120-pose window of sphere2500 as its odometry composes it (the initial guess)."""
    lines = _data("sphere2500.txt").splitlines()
    first, count = 300, 120
    kept = []
    for line in lines:
        f = line.split()
        i, j = int(f[1]), int(f[2])
        if first <= i < first + count and first <= j < first + count:
            kept.append(" ".join(["EDGE3", str(i - first), str(j - first), *f[3:]]))
    graph = se3.parse_edge3("\n".join(kept))
    pts = se3.positions_from_first(graph.poses)
    loops = int(np.sum(graph.j - graph.i != 1))
    xmin, xmax = float(pts[:, 0].min()), float(pts[:, 0].max())
    ymin, ymax = float(pts[:, 1].min()), float(pts[:, 1].max())
    size = 260.0
    scale = size / max(xmax - xmin, ymax - ymin, 1e-9)

    def p(k: int) -> tuple[float, float]:
        return 30 + (pts[k, 0] - xmin) * scale, 40 + size - (pts[k, 1] - ymin) * scale

    body = [el("rect", x=20, y=30, width=size + 20, height=size + 20, fill="#fff", stroke="#999")]
    for a, b in zip(graph.i, graph.j, strict=True):
        if b - a != 1:
            (xa, ya), (xb, yb) = p(int(a)), p(int(b))
            body.append(
                el(
                    "line",
                    x1=xa,
                    y1=ya,
                    x2=xb,
                    y2=yb,
                    stroke="#2166ac",
                    stroke_width=0.6,
                    stroke_dasharray="2 2",
                )
            )
    body.append(polyline([p(k) for k in range(len(pts))], stroke="#b2182b", stroke_width=1.5))
    body.append(text(20, 20, f"poses {first}–{first + count - 1} of sphere2500, seen from above"))
    body.append(text(size + 50, 60, "odometry (solid)", fill="#b2182b"))
    body.append(text(size + 50, 80, f"{loops} loop closures", fill="#2166ac"))
    body.append(text(size + 50, 96, "(dashed)", fill="#2166ac"))
    desc = (
        f"A window of {count} consecutive poses of sphere2500 with its {loops} loop closures, "
        "drawn from above at the initial guess the composed odometry gives (x and y seen from "
        f"its first pose; {fmt(xmax - xmin)} m by {fmt(ymax - ymin)} m). The optimum is what "
        "your optimiser computes."
    )
    return document(size + 200, size + 60, "A window of sphere2500 before optimising", desc, body)


FIGURES: dict[str, Figure] = {
    "se3/log-accuracy": log_accuracy,
    "se3/sphere": sphere_figure,
}

PICTURES: dict[str, Picture] = {
    "se3/so3-log": given(lambda p: _so3_picture()),
    "se3/optimise-3d": given(lambda p: _window_picture()),
}
