"""Chapter ``ekf-slam``: a new landmark initialised from one range-bearing measurement, and how
its uncertainty inherits the robot's."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, INK, ORANGE, Chart, Plane
from slamcourse.plots.ch_state import covariance_blocks
from slamcourse.plots.picture import Figure, Picture, answer, given
from slamcourse.plots.svg import num
from slamcourse.slam.ekfslam import augment

P_LESSON = [[0.04, 0.01, 0.002], [0.01, 0.03, -0.001], [0.002, -0.001, 0.01]]
R_LESSON = [[0.01, 0.0005], [0.0005, 0.0004]]


def landmark_init(
    mu: Sequence[float],
    P: Sequence[Sequence[float]],
    z: Sequence[float],
    R: Sequence[Sequence[float]],
    *,
    show_results: bool = True,
) -> str:
    """The robot (2σ position ellipse), the measured range and bearing, and the new landmark
    with its 2σ ellipse from :func:`slamcourse.slam.ekfslam.augment` ("?" while asked)."""
    mu2, P2 = augment(mu, P, z, R)
    x, y, th = (float(v) for v in mu[:3])
    lx, ly = float(mu2[-2]), float(mu2[-1])
    plane = Plane(
        [(x - 0.8, y - 0.8), (x + 0.8, y + 0.8), (lx - 0.8, ly - 0.8), (lx + 0.8, ly + 0.8)],
        width=500,
        height=380,
        pad=30,
        grid=1.0,
    )
    Pm = np.asarray(P, float)
    plane.ellipse(x, y, Pm[:2, :2], k=2.0, colour=BLUE, fill=BLUE)
    plane.segment((x, y), (lx, ly), colour=ORANGE, dash="6 4")
    plane.pose(x, y, th, colour=BLUE, label=f"robot ({num(x)}, {num(y)}, {num(th)})")
    plane.label(
        (x + lx) / 2,
        (y + ly) / 2,
        f"z = ({num(z[0])} m, {num(z[1])} rad)",
        colour=ORANGE,
        bold=True,
    )
    if show_results:
        plane.ellipse(lx, ly, P2[-2:, -2:], k=2.0, colour=GREEN, fill=GREEN)
        plane.point(lx, ly, colour=GREEN, label=f"landmark ({num(lx)}, {num(ly)})")
        a = 2 * math.sqrt(max(np.linalg.eigvalsh(P2[-2:, -2:])))
        facts = (
            f"The new landmark is at ({num(lx)}, {num(ly)}) m; its 2σ ellipse (half-axis "
            f"up to {num(a)} m) is wider than the robot's, since it inherits the robot's "
            "position and heading uncertainty, the heading's stretched by the range, plus "
            "the sensor's."
        )
    else:
        plane.point(lx, ly, colour=GREEN, shape="ring", label="landmark = ?")
        facts = "Where the landmark is, and how uncertain, is asked."
    desc = (
        f"The robot at ({num(x)}, {num(y)}) m facing {num(th)} rad, with its 2σ position "
        f"ellipse, measures a new landmark at range {num(z[0])} m and bearing {num(z[1])} rad. "
        + facts
    )
    return plane.svg("Initialising a landmark from one measurement", desc)


def before_update(P: Sequence[Sequence[float]], landmark: Sequence[float]) -> str:
    """The robot at the origin facing 0 and one landmark, each with its 2σ ellipse from the
    blocks of ``P`` (pose first, then the landmark): the state an update starts from."""
    Pm = np.asarray(P, float)
    lx, ly = float(landmark[0]), float(landmark[1])
    plane = Plane(
        [(-1.2, -1.2), (1.2, 1.2), (lx - 1.6, ly - 1.6), (lx + 1.6, ly + 1.6)],
        width=460,
        height=400,
        pad=30,
        grid=1.0,
    )
    plane.ellipse(0, 0, Pm[:2, :2], k=2.0, colour=BLUE, fill=BLUE)
    plane.ellipse(lx, ly, Pm[3:5, 3:5], k=2.0, colour=GREEN, fill=GREEN)
    plane.segment((0, 0), (lx, ly), colour=ORANGE, dash="6 4")
    plane.pose(0, 0, 0, colour=BLUE, label="robot (0, 0, 0)")
    plane.point(lx, ly, colour=GREEN, label=f"landmark ({num(lx)}, {num(ly)})")
    desc = (
        f"The robot at the origin and a landmark at ({num(lx)}, {num(ly)}) m, each with the 2σ "
        "ellipse of its block of P, before a range-bearing measurement of the landmark "
        "updates them (the measurement's line of sight dashed)."
    )
    return plane.svg("The state before an update", desc)


def scalar_update(var_prior: float, var_meas: float, *, show_results: bool = True) -> str:
    """Densities of a 1-D prior (mean 0) and a measurement (mean 1) and, when shown, the
    fused estimate: mean K = p / (p + r), variance (1 − K) p."""
    gain = var_prior / (var_prior + var_meas)
    post = (1 - gain) * var_prior
    spread = 3.2 * math.sqrt(max(var_prior, var_meas))
    xs = [-spread + (1 + 2 * spread) * k / 200 for k in range(201)]

    def density(x: float, mean: float, var: float) -> float:
        return math.exp(-((x - mean) ** 2) / (2 * var)) / math.sqrt(2 * math.pi * var)

    top = max(density(0, 0, v) for v in (var_prior, var_meas, post if show_results else 1e9))
    chart = Chart(
        (xs[0], xs[-1]), (0.0, top * 1.35), x_label="value (units of the state)", y_label="density"
    )
    chart.line([(x, density(x, 0.0, var_prior)) for x in xs], colour=BLUE)
    chart.line([(x, density(x, 1.0, var_meas)) for x in xs], colour=ORANGE, dash="6 4")
    legend = [
        (f"prior: mean 0, variance {num(var_prior)}", BLUE, ""),
        (f"measurement: 1, variance {num(var_meas)}", ORANGE, "6 4"),
    ]
    if show_results:
        chart.line([(x, density(x, gain, post)) for x in xs], colour=GREEN, width=2.5)
        legend.append((f"update: mean K = {num(gain)}, variance {num(post)}", GREEN, ""))
    desc = (
        f"A prior of variance {num(var_prior)} centred at 0 and a measurement of variance "
        f"{num(var_meas)} reading 1. "
        + (
            f"The update moves the estimate the fraction K = {num(gain)} of the way to the "
            f"measurement, and its variance falls to {num(post)}, below both."
            if show_results
            else "How far the update moves the estimate, K = ?, is asked."
        )
    )
    return chart.svg("A one-dimensional Kalman update", desc, legend)


def correlated_prior(pxx: float, pyy: float, pxy: float, rxx: float) -> str:
    """The 2σ ellipse of a correlated 2-D prior and the band of a measurement of x alone."""
    plane = Plane(
        [
            (-2.4 * math.sqrt(pxx), -2.4 * math.sqrt(pyy)),
            (2.4 * math.sqrt(pxx), 2.4 * math.sqrt(pyy)),
        ],
        width=420,
        height=360,
        pad=30,
    )
    plane.ellipse(0, 0, [[pxx, pxy], [pxy, pyy]], k=2.0, colour=BLUE, fill=BLUE)
    w = 2 * math.sqrt(rxx)
    for x in (-w, w):
        plane.segment((x, plane.y0 - 1), (x, plane.y1 + 1), colour=ORANGE, dash="6 4")
    plane.point(0, 0, colour=INK, shape="cross", label="prior mean")
    desc = (
        f"The prior's 2σ ellipse, with variances {num(pxx)} (x) and {num(pyy)} (y) and "
        f"covariance {num(pxy)}: tilted, because the errors of x and y go together. The dashed "
        f"lines are ±2σ of a measurement of x alone (variance {num(rxx)}): it says nothing "
        "about y directly, yet through the tilt it moves y too."
    )
    return plane.svg("A correlated prior and a measurement of one coordinate", desc)


FIGURES: dict[str, Figure] = {
    "ekf-slam/landmark-init": lambda: landmark_init(
        [1.0, 0.5, 0.8], P_LESSON, [3.0, -0.4], R_LESSON
    ),
}

PICTURES: dict[str, Picture] = {
    "ekf-slam/landmark-position": Picture(
        lambda p, shown: landmark_init(
            [float(p["x"]), float(p["y"]), float(p["t"])],
            P_LESSON,
            [float(p["rng"]), float(p["brg"])],
            R_LESSON,
            show_results=shown,
        )
    ),
    "ekf-slam/augment": given(
        lambda p: landmark_init([2, 1, 0.5], P_LESSON, [4, 0.3], R_LESSON, show_results=False)
    ),
    "ekf-slam/update-covariance": given(
        lambda p: before_update(
            [
                [0.1, 0, 0, 0.05, 0],
                [0, 0.1, 0, 0, 0.05],
                [0, 0, 0.01, 0, 0],
                [0.05, 0, 0, 0.5, 0],
                [0, 0.05, 0, 0, 0.5],
            ],
            [3.0, 4.0],
        )
    ),
    "ekf-slam/scalar-gain": Picture(
        lambda p, shown: scalar_update(
            float(p["var_prior"]), float(p["var_meas"]), show_results=shown
        )
    ),
    "ekf-slam/correlated-update": given(
        lambda p: correlated_prior(
            float(p["pxx"]), float(p["pyy"]), float(p["pxy"]), float(p["rxx"])
        )
    ),
    # the blocks a new landmark adds are what the exercise counts
    "ekf-slam/new-entries": answer(lambda p: covariance_blocks(3, 2, int(p["landmarks"]) + 1)),
}
