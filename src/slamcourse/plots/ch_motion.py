"""Chapter ``motion``: the odometry motion (δrot1, δtrans, δrot2), and the banana-shaped cloud
of sampled poses against the EKF's linearised ellipse."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, PURPLE, Plane
from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.svg import el, num
from slamcourse.slam.ekf import odometry_step, predict


def odometry_figure(pose: Sequence[float], u: Sequence[float], *, show_results: bool = True) -> str:
    """The start pose, the turn δrot1, the straight drive δtrans, the turn δrot2 and the end
    pose ("?" while an exercise asks for it)."""
    x, y, th = (float(v) for v in pose)
    rot1, trans, rot2 = (float(v) for v in u)
    end = odometry_step((x, y, th), (rot1, trans, rot2))
    pad = max(0.6, 0.35 * trans)
    plane = Plane(
        [
            (x - pad, y - pad),
            (x + pad, y + pad),
            (end[0] - pad, end[1] - pad),
            (end[0] + pad, end[1] + pad),
        ],
        width=480,
        height=380,
        pad=30,
        grid=1.0,
    )
    arm = 0.3 * max(trans, 1.0)
    plane.segment(
        (x, y), (x + arm * math.cos(th), y + arm * math.sin(th)), colour=MUTED, dash="4 3"
    )
    plane.segment((x, y), (end[0], end[1]), colour=BLUE, width=2.0, arrow=True)
    plane.segment(
        (end[0], end[1]),
        (end[0] + arm * math.cos(th + rot1), end[1] + arm * math.sin(th + rot1)),
        colour=MUTED,
        dash="4 3",
    )
    for (cx, cy), a0, da, name, colour in (
        ((x, y), th, rot1, "δrot1", ORANGE),
        ((end[0], end[1]), th + rot1, rot2, "δrot2", PURPLE),
    ):
        r = 0.22 * arm * 3
        steps = 16
        pts = [
            (cx + r * math.cos(a0 + da * k / steps), cy + r * math.sin(a0 + da * k / steps))
            for k in range(steps + 1)
        ]
        plane.path(pts, colour=colour, width=2.0)
        mid = pts[steps // 2]
        plane.label(mid[0], mid[1], f"{name} = {num(da)} rad", colour=colour, bold=True)
    plane.pose(x, y, th, colour=INK, label=f"start ({num(x)}, {num(y)}, {num(th)})")
    if show_results:
        plane.pose(*end, colour=GREEN, label=f"end ({num(end[0])}, {num(end[1])}, {num(end[2])})")
    else:
        plane.point(end[0], end[1], colour=GREEN, shape="ring", label="end = ?")
    plane.label(
        (x + end[0]) / 2, (y + end[1]) / 2, f"δtrans = {num(trans)} m", colour=BLUE, bold=True
    )
    desc = (
        f"The robot starts at ({num(x)}, {num(y)}) m facing {num(th)} rad, turns by δrot1 = "
        f"{num(rot1)} rad, drives δtrans = {num(trans)} m straight and turns by δrot2 = "
        f"{num(rot2)} rad"
        + (
            f", ending at ({num(end[0])}, {num(end[1])}) m facing {num(end[2])} rad."
            if show_results
            else "; where it ends is asked."
        )
    )
    return plane.svg("The odometry motion model", desc)


def banana_figure(
    trans: float = 1.0,
    steps: int = 10,
    sigma_rot: float = 0.12,
    sigma_trans: float = 0.02,
    samples: int = 600,
    seed: int = 2,
) -> str:
    """``samples`` robots drive ``steps`` steps of ``trans`` m, each with noisy rotations and
    translations: their end points curve into a banana, while the EKF (the same motion,
    linearised) predicts one ellipse."""
    rng = np.random.default_rng(seed)
    ends = []
    for _ in range(samples):
        pose = (0.0, 0.0, 0.0)
        for _ in range(steps):
            u = (
                rng.normal(0, sigma_rot),
                trans + rng.normal(0, sigma_trans),
                rng.normal(0, sigma_rot),
            )
            pose = odometry_step(pose, u)
        ends.append(pose)
    mean: tuple[float, float, float] = (0.0, 0.0, 0.0)
    cov = np.zeros((3, 3))
    m = np.diag([sigma_rot**2, sigma_trans**2, sigma_rot**2])
    path = [(0.0, 0.0)]
    for _ in range(steps):
        mean, cov = predict(mean, cov, (0.0, trans, 0.0), m)
        path.append((mean[0], mean[1]))
    xs = [e[0] for e in ends]
    ys = [e[1] for e in ends]
    plane = Plane(
        [(0.0, min(ys)), (max(xs), max(ys)), (0.0, 0.0)], width=540, height=360, pad=30, top=10
    )
    for ex, ey, _ in ends:
        plane.body.append(
            el("circle", cx=plane.sx(ex), cy=plane.sy(ey), r=1.6, fill=BLUE, fill_opacity="0.45")
        )
    plane.path(path, colour=INK, dash="4 3", width=1.2)
    plane.ellipse(mean[0], mean[1], cov[:2, :2], k=2.0, colour=ORANGE)
    plane.ellipse(mean[0], mean[1], cov[:2, :2], k=1.0, colour=ORANGE, dash="4 3")
    plane.pose(0, 0, 0, colour=INK, label="start")
    plane.point(mean[0], mean[1], colour=ORANGE, shape="cross", label="EKF mean")
    inside = 0
    inv = np.linalg.inv(cov[:2, :2])
    for ex, ey, _ in ends:
        d = np.array([ex - mean[0], ey - mean[1]])
        inside += float(d @ inv @ d) <= 4.0
    desc = (
        f"{samples} simulated robots drive {steps} steps of {num(trans)} m with rotation noise "
        f"{num(sigma_rot)} rad and translation noise {num(sigma_trans)} m (1σ) per step. Their "
        "end points (dots) curve into a banana, since a heading error swings the rest of the "
        "path around an arc. The EKF, linearising the same motion, predicts the ellipses (1σ "
        f"dashed, 2σ solid), which cannot bend: {inside} of the {samples} end points fall "
        f"inside its 2σ ellipse, where a Gaussian would hold {num(100 * (1 - math.exp(-2)))}%."
    )
    legend = [
        ("sampled end points", BLUE, "marker:circle"),
        ("EKF 1σ, 2σ", ORANGE, ""),
        ("mean path", INK, "4 3"),
    ]
    return plane.svg("Sampled poses against the EKF ellipse", desc, legend)


def covariance_figure(
    pose: Sequence[float],
    u: Sequence[float],
    sigma: Sequence[Sequence[float]],
    motion: Sequence[Sequence[float]],
) -> str:
    """The position covariance before and after one prediction (1σ ellipses)."""
    mean2, cov2 = predict(pose, sigma, u, motion)
    s0 = np.asarray(sigma, float)
    plane = Plane(
        [
            (pose[0] - 0.6, pose[1] - 0.6),
            (mean2[0] + 0.6, mean2[1] + 0.6),
            (pose[0] + 0.6, pose[1] + 0.6),
            (mean2[0] - 0.6, mean2[1] - 0.6),
        ],
        width=480,
        height=300,
        pad=30,
    )
    plane.ellipse(pose[0], pose[1], s0[:2, :2], k=2.0, colour=BLUE)
    plane.ellipse(mean2[0], mean2[1], cov2[:2, :2], k=2.0, colour=ORANGE)
    plane.pose(*pose, colour=BLUE, label="before")
    plane.pose(*mean2, colour=ORANGE, label="after the motion")
    motion_text = ", ".join(num(float(v)) for v in u)
    start_text = ", ".join(num(float(v)) for v in pose)
    desc = (
        f"The robot's position uncertainty (2σ ellipses) before and after the motion "
        f"({motion_text}) predicted from ({start_text}): "
        "the heading uncertainty turns into sideways uncertainty, so the ellipse grows across "
        "the direction of travel."
    )
    return plane.svg("Covariance before and after a prediction", desc)


FIGURES: dict[str, Figure] = {
    "motion/odometry-model": lambda: odometry_figure((0.5, 0.5, 0.3), (0.6, 2.0, -0.8)),
    "motion/banana": banana_figure,
}

PICTURES: dict[str, Picture] = {
    "motion/step-value": Picture(
        lambda p, shown: odometry_figure(
            (float(p["x"]), float(p["y"]), float(p["t"])),
            (float(p["rot1"]), float(p["trans"]), float(p["rot2"])),
            show_results=shown,
        )
    ),
    "motion/odometry-step": given(
        lambda p: odometry_figure((0, 0, 0), (0.4, 2.0, -0.3), show_results=False)
    ),
    "motion/predict-covariance": given(
        lambda p: covariance_figure(
            (0, 0, 0),
            (0, 2, 0),
            np.diag([0.01, 0.01, 0.004]).tolist(),
            np.diag([0.003, 0.02, 0.001]).tolist(),
        )
    ),
    "motion/lateral-variance": given(
        lambda p: covariance_figure(
            (0, 0, 0),
            (0, float(p["trans"]), 0),
            np.diag([0.0, float(p["var_y"]), float(p["var_t"])]).tolist(),
            np.diag([float(p["var_rot1"]), 0.0, 0.0]).tolist(),
        )
    ),
}
