"""Chapter ``victoria-park``: the park's drive and trees, the sparsity of its ``H``, the check
of the measurement model on the residuals, and EKF-SLAM's map against the graph's.

Prose figures (no arguments; drawn from :mod:`slamcourse.slam.victoria` and the data that
ship in ``exercises/victoria-park/data``):

- ``victoria-park/park``: dead reckoning against the optimum of the whole park, with its trees;
- ``victoria-park/sparsity``: the non-zero blocks of ``H`` for the first poses of the drive;
- ``victoria-park/residuals``: radial and sideways RMS residuals of the LANDMARK lines at the
  optimum, by range, against the file's σ and GTSAM's reading;
- ``victoria-park/ekf-vs-graph``: the trees where EKF-SLAM leaves them and where the batch
  optimum puts them.

Pictures of the exercises draw givens only (a pose and a tree, a small piece of the file).
"""

from __future__ import annotations

import functools
import itertools
import math
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, PURPLE, Chart, Plane
from slamcourse.plots.picture import Figure, Params, Picture, answer, given
from slamcourse.plots.svg import document, el, num, text
from slamcourse.slam import victoria as vp

Array = NDArray[np.float64]
STRIDE = 2000
SPARSITY_POSES = 40
RANGE_BINS = (4.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 21.0)


def _data_path() -> Path:
    from slamcourse.course.locate import bundled_course_root

    return bundled_course_root() / "exercises" / "victoria-park" / "data" / "victoria_park.txt"


@functools.cache
def park_text() -> str:
    return _data_path().read_text(encoding="utf-8")


@functools.cache
def park() -> vp.LandmarkData:
    return vp.parse_victoria(park_text())


@functools.cache
def optimum() -> tuple[Array, Array]:
    """The whole park optimised in batches of 2000 poses (poses n×3, trees m×2)."""
    x, landmarks, _ = vp.incremental(park(), STRIDE)
    return x, landmarks


@functools.cache
def ekf_run() -> vp.EkfRun:
    return vp.ekf_slam(park())


# --- victoria-park/park -----------------------------------------------------------------------


def park_figure() -> str:
    data = park()
    before, _ = vp.initial_guess(data)
    after, trees = optimum()
    pts = [(float(a), float(b)) for a, b in np.vstack([before[:, :2], after[:, :2], trees])]
    plane = Plane(pts, width=600, height=480, pad=20, top=70)
    plane.path(
        [(float(a), float(b)) for a, b, _ in before], colour=ORANGE, dash="5 3", width=1.0, every=4
    )
    plane.path([(float(a), float(b)) for a, b, _ in after], colour=BLUE, width=1.0, every=4)
    for a, b in trees:
        plane.point(float(a), float(b), colour=GREEN, shape="diamond", size=3.0)
    end = float(np.hypot(*(before[-1, :2] - after[-1, :2])))
    length = float(np.sum(np.hypot(*np.diff(before[:, :2], axis=0).T)))
    desc = (
        f"The Victoria Park drive: {data.n} poses over about {num(length / 1000, 2)} km and "
        f"{data.m} trees. Dead reckoning from the odometry (dashed) bends away from the "
        f"optimum of the landmark pose graph (solid) and ends {num(end, 3)} m from it; the "
        "trees (diamonds) are drawn where the optimum puts them, along the paths of the park."
    )
    legend = [
        ("dead reckoning (odometry only)", ORANGE, "5 3"),
        ("optimum of the landmark graph", BLUE, ""),
        ("trees at the optimum", GREEN, "marker:diamond"),
    ]
    return plane.svg("Victoria Park: dead reckoning and the optimum", desc, legend)


# --- victoria-park/sparsity -------------------------------------------------------------------


def sparsity_cells(poses: int = SPARSITY_POSES) -> tuple[int, int, set[tuple[int, int]]]:
    """The first ``poses`` poses of the park and the trees they see: (poses, trees, the
    non-zero blocks (row, column) of their ``H``, poses first)."""
    sub = vp.subproblem(park(), poses)
    cells = {(k, k) for k in range(sub.n + sub.m)}
    for i, j in zip(sub.odometry_from, sub.odometry_to, strict=True):
        cells |= {(int(i), int(j)), (int(j), int(i))}
    for i, lm in zip(sub.seen_from, sub.seen, strict=True):
        a, b = int(i), sub.n + int(lm)
        cells |= {(a, b), (b, a)}
    return sub.n, sub.m, cells


def sparsity_figure() -> str:
    n, m, cells = sparsity_cells()
    size = 8.0
    side = size * (n + m)
    x0, y0 = 70.0, 50.0
    body = [el("rect", x=0.0, y=0.0, width=side + 250, height=side + 110, fill="#fff")]
    body.append(el("rect", x=x0, y=y0, width=side, height=side, fill="#fbfbf8", stroke="#888"))
    for r, c in sorted(cells):
        body.append(
            el(
                "rect",
                x=x0 + c * size + 0.5,
                y=y0 + r * size + 0.5,
                width=size - 1.0,
                height=size - 1.0,
                fill="#1f4e79" if r < n and c < n else PURPLE,
            )
        )
    edge = x0 + n * size
    body.append(
        el("line", x1=edge, y1=y0, x2=edge, y2=y0 + side, stroke=INK, stroke_dasharray="4 3")
    )
    body.append(
        el(
            "line",
            x1=x0,
            y1=y0 + n * size,
            x2=x0 + side,
            y2=y0 + n * size,
            stroke=INK,
            stroke_dasharray="4 3",
        )
    )
    body.append(text(x0 + n * size / 2, y0 - 10, f"{n} poses", text_anchor="middle", fill=INK))
    body.append(text(edge + m * size / 2 + 4, y0 - 10, f"{m} trees", text_anchor="start", fill=INK))
    lx = x0 + side + 20
    body += [
        el("rect", x=lx, y=y0 + 10, width=12.0, height=12.0, fill="#1f4e79"),
        text(lx + 18, y0 + 20, "pose–pose block", fill=INK),
        el("rect", x=lx, y=y0 + 32, width=12.0, height=12.0, fill=PURPLE),
        text(lx + 18, y0 + 42, "block with a tree", fill=INK),
    ]
    total = (n + m) ** 2
    pose_tree = sum(1 for r, c in cells if (r < n) != (c < n))
    desc = (
        f"The block pattern of H for the first {n} poses of the park and the {m} trees they "
        f"see, poses first: {len(cells)} of {total} blocks are non-zero. The poses form a "
        f"block-tridiagonal band (the odometry chain); {pose_tree} blocks in the border join a "
        "pose to a tree it saw; the trees' own part is diagonal, since two trees are never "
        "measured against each other."
    )
    return document(side + 250, side + 110, "Sparsity of H for a piece of the park", desc, body)


# --- victoria-park/residuals ------------------------------------------------------------------


def residual_profile() -> list[tuple[float, int, float, float]]:
    """Per range bin of the LANDMARK lines at the optimum: (mean range, lines, RMS of the
    residual along the line of sight, RMS across it), in metres."""
    x, trees = optimum()
    data = park()
    e, _, _ = vp.xy_terms(x, trees, data)
    z = data.measured
    r = np.hypot(z[:, 0], z[:, 1])
    u = z / r[:, None]
    along = np.einsum("ki,ki->k", e, u)
    across = e[:, 1] * u[:, 0] - e[:, 0] * u[:, 1]
    out = []
    for lo, hi in itertools.pairwise(RANGE_BINS):
        k = (r >= lo) & (r < hi)
        out.append(
            (
                float(r[k].mean()),
                int(k.sum()),
                float(np.sqrt(np.mean(along[k] ** 2))),
                float(np.sqrt(np.mean(across[k] ** 2))),
            )
        )
    return out


def residuals_figure() -> str:
    profile = residual_profile()
    c11 = float(park().measured_cov[0, 0, 0])
    sigma_b, sigma = vp.gtsam_sigmas(c11)
    chart = Chart(
        (4.0, 21.0),
        (0.0, 2.2),
        x_label="range of the line (m)",
        y_label="RMS residual (m)",
        width=600,
        height=340,
    )
    chart.hline(sigma, colour=INK, dash="6 4")
    chart.line([(4.0, 4.0 * sigma_b), (11.0, 11.0 * sigma_b)], colour=ORANGE, dash="2 3")
    along = [(p[0], p[2]) for p in profile]
    across = [(p[0], p[3]) for p in profile]
    chart.line(along, colour=BLUE)
    chart.points(along, colour=BLUE, shape="square", size=3.5)
    chart.line(across, colour=GREEN, dash="8 3")
    chart.points(across, colour=GREEN, shape="circle", size=3.5)
    rows = "; ".join(
        f"{num(p[0], 3)} m ({p[1]} lines): along {num(p[2], 2)} m, across {num(p[3], 2)} m"
        for p in profile
    )
    desc = (
        "Root-mean-square residual of the LANDMARK lines at the optimum, by range: along the "
        f"line of sight and across it. By range bin: {rows}. The file's σ of "
        f"{num(sigma, 2)} m (dashed) lies above every bin; GTSAM's bearing σ of "
        f"{num(sigma_b, 2)} rad carried to the range (dotted, cut at 11 m) grows to "
        f"{num(10 * sigma_b, 2)} m at 10 m."
    )
    legend = [
        ("along the line of sight", BLUE, "marker:square"),
        ("across it (sideways)", GREEN, "marker:circle"),
        (f"file's σ = √{num(c11)} m", INK, "6 4"),
        ("GTSAM's bearing σ × range", ORANGE, "2 3"),
    ]
    return chart.svg("Residuals of the LANDMARK lines at the optimum", desc, legend)


# --- victoria-park/ekf-vs-graph ---------------------------------------------------------------


def ekf_gaps() -> tuple[Array, Array]:
    """The trees where EKF-SLAM leaves them and where the optimum puts them, both m×2 in the
    order the filter added them."""
    run = ekf_run()
    order = np.array(run.order, dtype=np.intp)
    filtered = run.mean[3:].reshape(-1, 2)
    return filtered, optimum()[1][order]


def ekf_figure() -> str:
    filtered, smoothed = ekf_gaps()
    after, _ = optimum()
    pts = [(float(a), float(b)) for a, b in np.vstack([filtered, smoothed, after[:, :2]])]
    plane = Plane(pts, width=600, height=480, pad=20, top=70)
    plane.path([(float(a), float(b)) for a, b, _ in after], colour="#bbbbbb", width=0.8, every=6)
    for f, s in zip(filtered, smoothed, strict=True):
        plane.body.append(
            el(
                "line",
                x1=plane.sx(float(f[0])),
                y1=plane.sy(float(f[1])),
                x2=plane.sx(float(s[0])),
                y2=plane.sy(float(s[1])),
                stroke=MUTED,
                stroke_width=0.8,
            )
        )
    for a, b in smoothed:
        plane.point(float(a), float(b), colour=BLUE, shape="diamond", size=3.0)
    for a, b in filtered:
        plane.point(float(a), float(b), colour=ORANGE, shape="circle", size=2.5)
    gap = np.hypot(*(filtered - smoothed).T)
    desc = (
        f"The {len(gap)} trees as EKF-SLAM leaves them after the last line (circles) and as "
        f"the batch optimum puts them (diamonds), joined by grey lines, over the optimised "
        f"drive (light grey). They are {num(float(gap.mean()), 3)} m apart on average and up to "
        f"{num(float(gap.max()), 3)} m; the filter's own 95 % ellipses are far smaller than "
        "these gaps."
    )
    legend = [
        ("trees, EKF-SLAM", ORANGE, "marker:circle"),
        ("trees, batch optimum", BLUE, "marker:diamond"),
        ("optimised drive", "#bbbbbb", ""),
    ]
    return plane.svg("EKF-SLAM's map against the batch optimum", desc, legend)


# --- pictures ---------------------------------------------------------------------------------


def jacobian_picture(pose: tuple[float, float, float], tree: tuple[float, float]) -> str:
    """A pose with its axes and a tree, the offset between them dashed (givens only)."""
    x, y, t = pose
    span = max(abs(tree[0] - x), abs(tree[1] - y), 4.0)
    plane = Plane(
        [(x, y), tree, (x - 0.3 * span, y - 0.3 * span)], width=420, height=340, pad=40, top=20
    )
    plane.segment((x, y), tree, colour=MUTED, dash="4 3")
    plane.pose(x, y, t, colour=BLUE, label="pose (x, y, θ)", axes=0.35 * span)
    plane.point(tree[0], tree[1], colour=GREEN, label="tree l")
    desc = (
        f"The robot at ({num(x, 4)}, {num(y, 4)}) m facing {num(t, 3)} rad with its own x and "
        f"y axes, and a tree at ({num(tree[0], 4)}, {num(tree[1], 4)}) m; the dashed line is "
        "the offset l − t that the LANDMARK line measures in the robot's frame."
    )
    return plane.svg("A pose and a tree", desc)


def xy_error_picture(p: Params) -> str:
    x, y, t = float(p["xr"]), float(p["yr"]), float(p["tr"])
    lx, ly = float(p["lx"]), float(p["ly"])
    seen = vp.inverse_landmark((x, y, t), (float(p["zx"]), float(p["zy"])))
    plane = Plane(
        [(x, y), (lx, ly), (float(seen[0]), float(seen[1]))], width=440, height=340, pad=40, top=20
    )
    plane.segment((x, y), (lx, ly), colour=GREEN, dash="4 3")
    plane.segment((x, y), (float(seen[0]), float(seen[1])), colour=ORANGE, dash="2 3")
    plane.pose(x, y, t, colour=BLUE, label="pose", axes=3.0)
    plane.point(
        float(seen[0]), float(seen[1]), colour=ORANGE, shape="ring", label="where z puts it"
    )
    plane.point(lx, ly, colour=GREEN, label="tree estimate l")
    desc = (
        f"The pose ({num(x, 4)}, {num(y, 4)}, {num(t, 3)}) with its axes, the tree's estimate at "
        f"({num(lx, 4)}, {num(ly, 4)}), and the point the line's z = ({num(float(p['zx']), 4)}, "
        f"{num(float(p['zy']), 4)}) puts in the world from this pose."
    )
    return plane.svg("One LANDMARK line", desc)


def sideways_picture(p: Params) -> str:
    """A tree ``r`` m ahead and GTSAM's ±1σ bearing wedge (the answer: its half-width)."""
    c11, r = float(p["c11"]), float(p["r"])
    sb, _ = vp.gtsam_sigmas(c11)
    plane = Plane(
        [(0.0, 0.0), (r, 0.0), (r, r * math.tan(sb)), (r, -r * math.tan(sb))],
        width=440,
        height=300,
        pad=40,
        top=20,
    )
    for sign in (1.0, -1.0):
        plane.segment((0.0, 0.0), (r, sign * r * math.tan(sb)), colour=ORANGE, dash="4 3")
    plane.segment((r, -r * sb), (r, r * sb), colour=ORANGE, width=2.5)
    plane.pose(0.0, 0.0, 0.0, colour=BLUE, label="robot")
    plane.point(r, 0.0, colour=GREEN, label=f"tree at {num(r)} m")
    plane.label(r, r * sb, f"± {num(r * sb, 3)} m", colour=ORANGE)
    desc = (
        f"A tree {num(r)} m ahead and GTSAM's one-sigma bearing wedge of ±{num(sb, 3)} rad: "
        f"sideways ±{num(r * sb, 3)} m at the tree."
    )
    return plane.svg("GTSAM's bearing noise at the tree", desc)


def head_picture() -> str:
    """The first 30 lines of the park: the initial guess of 20 poses and its two trees."""
    head = "\n".join(park_text().splitlines()[:30]) + "\n"
    data = vp.parse_victoria(head)
    x, trees = vp.initial_guess(data)
    pts = [(float(a), float(b)) for a, b in np.vstack([x[:, :2], trees])]
    plane = Plane(pts, width=460, height=320, pad=40, top=20)
    for i, lm in zip(data.seen_from, data.seen, strict=True):
        plane.segment(
            (float(x[i, 0]), float(x[i, 1])),
            (float(trees[lm, 0]), float(trees[lm, 1])),
            colour="#cccccc",
            width=0.8,
        )
    plane.path([(float(a), float(b)) for a, b, _ in x], colour=BLUE, width=2.0)
    for k, (a, b) in enumerate(trees):
        plane.point(float(a), float(b), colour=GREEN, label=f"tree {data.landmark_ids[k]}")
    desc = (
        f"The first 30 lines of the park: {data.n} poses chained by odometry (the car has just "
        f"started and moves {num(float(np.hypot(*(x[-1, :2] - x[0, :2]))), 3)} m), and "
        f"{data.m} trees placed at their first sighting, with a grey line for each of the "
        f"{len(data.measured)} LANDMARK lines."
    )
    return plane.svg("The first lines of the park, as the initial guess", desc)


FIGURES: dict[str, Figure] = {
    "victoria-park/park": park_figure,
    "victoria-park/sparsity": sparsity_figure,
    "victoria-park/residuals": residuals_figure,
    "victoria-park/ekf-vs-graph": ekf_figure,
}

PICTURES: dict[str, Picture] = {
    "victoria-park/landmark-jacobian": given(
        lambda p: jacobian_picture((-30.0, -13.38, 0.339), (-22.56, -3.19))
    ),
    "victoria-park/optimise-landmarks": given(lambda p: head_picture()),
    "victoria-park/xy-error": given(xy_error_picture),
    "victoria-park/gtsam-sideways": answer(sideways_picture),
    "victoria-park/nonzero-blocks": given(lambda p: sparsity_figure()),
}
