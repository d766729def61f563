"""Figures and pictures of the passages that close the teaching gaps of chapters 6, 8, 12 and
13 (issue 16): the four (R, t) candidates of an essential matrix, a prior other than one half,
and the givens of the new code exercises."""

from __future__ import annotations

import itertools
import math

import numpy as np

from slamcourse.plots import ch_jcbb
from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, Chart, Plane
from slamcourse.plots.picture import Figure, Picture, given
from slamcourse.plots.svg import num
from slamcourse.slam import ekf, ekfslam

# --- chapter 6: the four candidates of the sideways step ---------------------------------------

_W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def _candidates(e: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    u, _, vt = np.linalg.svd(e)
    u = u if np.linalg.det(u) > 0 else -u
    vt = vt if np.linalg.det(vt) > 0 else -vt
    return [(u @ w @ vt, s * u[:, 2]) for w in (_W, _W.T) for s in (1.0, -1.0)]


def _depths(r: np.ndarray, t: np.ndarray, x1: np.ndarray, x2: np.ndarray) -> tuple[float, float]:
    z, *_ = np.linalg.lstsq(np.column_stack([-(r @ x1), x2]), t, rcond=None)
    return float(z[0]), float(z[1])


def four_candidates() -> str:
    """The sideways step (t = (1, 0, 0), R = I) seen from above (x to the right, depth z up):
    for each of the four candidates, both cameras, the triangulated point and its depths."""
    e = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    x1, x2 = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 1.0])
    gap = 4.0
    plane = Plane([(-1.6, -1.8), (3 * gap + 1.6, 1.8)], width=720, height=250, pad=24)
    facts = []
    for k, (r, t) in enumerate(_candidates(e)):
        ox = k * gap
        z1, z2 = _depths(r, t, x1, x2)
        point = z1 * x1  # in camera 1's frame
        centre = -r.T @ t  # camera 2's centre in camera 1's frame
        axis = r.T @ np.array([0.0, 0.0, 1.0])  # camera 2's optical axis in camera 1's frame
        good = z1 > 0 and z2 > 0
        colour = GREEN if good else MUTED
        plane.segment((ox, 0.0), (ox + point[0], point[2]), colour=colour, dash="3 3")
        plane.segment(
            (ox + centre[0], centre[2]), (ox + point[0], point[2]), colour=colour, dash="3 3"
        )
        plane.pose(ox, 0.0, math.pi / 2, colour=BLUE, size=12)
        plane.pose(
            ox + centre[0],
            centre[2],
            math.atan2(axis[2], axis[0]),
            colour=ORANGE,
            size=12,
        )
        plane.point(ox + point[0], point[2], colour=colour, shape="circle", size=5)
        plane.label(ox, -1.5, f"({num(z1)}, {num(z2)})", colour=INK, bold=good)
        facts.append(
            f"candidate {k + 1}: camera 2 at x = {num(centre[0])} facing "
            f"{'forward' if axis[2] > 0 else 'backward'}, depths ({num(z1)}, {num(z2)})"
            + (", in front of both cameras" if good else "")
        )
    desc = (
        "Four panels, seen from above, of the sideways step t = (1, 0, 0), R = I with the point "
        "one unit straight ahead of camera 1 (blue); camera 2 is orange. " + "; ".join(facts) + "."
    )
    return plane.svg(
        "The four (R, t) candidates of one essential matrix",
        desc,
        [("camera 1", BLUE, ""), ("camera 2", ORANGE, ""), ("in front of both", GREEN, "")],
    )


def match_picture() -> str:
    """The givens of ``vision/decompose-essential``'s first example: the match in both images."""
    plane = Plane([(-1.5, -1.2), (4.5, 1.2)], width=520, height=240, pad=24)
    points = [((0.0, 0.0), "x1 = (0, 0)"), ((1.0, 0.0), "x2 = (1, 0)")]
    for k, ((u, v), name) in enumerate(points):
        ox = 3.0 * k
        corners = [(-1, -1), (1, -1), (1, 1), (-1, 1), (-1, -1)]
        for a, b in itertools.pairwise(corners):
            plane.segment((ox + a[0], a[1]), (ox + b[0], b[1]), colour=MUTED, width=1.0)
        plane.label(ox, 1.1, f"image {k + 1}", colour=INK)
        plane.point(ox + u, v, colour=BLUE if k == 0 else ORANGE, shape="circle", label=name)
    desc = (
        "The two normalised image planes (u to the right, v up, from −1 to 1). The match of the "
        "first example: x1 = (0, 0) in image 1, at the centre, and x2 = (1, 0) in image 2, one "
        "unit to the right."
    )
    return plane.svg("One match in two images", desc)


# --- chapter 8: the prior counted again ---------------------------------------------------------


def prior_readings(p0: float = 0.2, readings: int = 10) -> str:
    """The cell's probability after 0 … ``readings`` readings that carry no information
    (p(m | z) = p0), with the update right and with −l₀ forgotten."""
    l0 = math.log(p0 / (1 - p0))
    right = [(float(k), p0) for k in range(readings + 1)]
    wrong = [(float(k), 1 / (1 + math.exp(-(k + 1) * l0))) for k in range(readings + 1)]
    chart = Chart(
        (0.0, float(readings)),
        (1e-8, 100.0),
        x_label="readings that say nothing",
        y_label="p(occupied)",
        log_y=True,
    )
    chart.line(right, colour=GREEN)
    chart.line(wrong, colour=ORANGE, dash="6 4")
    chart.points(wrong, colour=ORANGE, shape="circle", size=3)
    desc = (
        f"A cell with prior {num(p0)} (l0 = {num(l0)}) and {readings} readings whose sensor "
        f"model returns the prior. With l ← l + logit p(m|z) − l0 the cell stays at {num(p0)}; "
        f"without −l0 each reading adds l0 again and the cell falls to "
        f"{wrong[-1][1]:.1e} after {readings} of them (logarithmic axis)."
    )
    return chart.svg(
        "A prior counted once per reading",
        desc,
        [("with −l0", GREEN, ""), ("without −l0", ORANGE, "6 4")],
    )


# --- chapter 12: the first example of the whole step ------------------------------------------


def slam_step_picture() -> str:
    """The givens of ``ekf-slam/slam-step``'s first example: the pose before and after the
    predicted motion, the mapped landmark, and where the two measurements point from there."""
    pose = (0.0, 0.0, 0.0)
    u = (0.1, 1.0, -0.05)
    landmark = (4.0, 3.0)
    zs = [(4.25, 0.62), (6.0, -1.0)]
    moved = ekf.odometry_step(pose, u)
    plane = Plane([(-1.0, -5.5), (6.5, 4.0)], width=460, height=420, pad=30)
    plane.pose(*pose, colour=MUTED)
    plane.label(pose[0], pose[1] - 0.5, "before", colour=MUTED)
    plane.pose(*moved, colour=BLUE, label="predicted")
    plane.point(*landmark, colour=GREEN, label="landmark 0")
    facts = []
    for k, z in enumerate(zs):
        end = ekfslam.inverse_observation(moved, z)
        plane.segment(
            (moved[0], moved[1]),
            (float(end[0]), float(end[1])),
            colour=ORANGE,
            dash="4 3",
            arrow=True,
        )
        plane.label(float(end[0]), float(end[1]), f"z{k + 1}", colour=ORANGE)
        facts.append(f"z{k + 1} = (range {num(z[0])} m, bearing {num(z[1])} rad)")
    desc = (
        "The robot at (0, 0) facing 0 rad, moved by the odometry (0.1 rad, 1 m, −0.05 rad) to "
        f"the predicted pose ({num(moved[0])}, {num(moved[1])}, {num(moved[2])}); the mapped "
        "landmark 0 at (4, 3) m; from the predicted pose, " + "; ".join(facts) + " (z1 is "
        "landmark 0, z2 a new landmark)."
    )
    return plane.svg("One EKF-SLAM step: the givens", desc)


FIGURES: dict[str, Figure] = {
    "vision/four-candidates": four_candidates,
    "occupancy/prior-readings": prior_readings,
}

PICTURES: dict[str, Picture] = {
    "vision/decompose-essential": given(lambda p: match_picture()),
    "ekf-slam/slam-step": given(lambda p: slam_step_picture()),
    "jcbb/jcbb-search": given(lambda p: ch_jcbb.scene()),
}
