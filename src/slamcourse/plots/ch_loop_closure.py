"""Chapter ``loop-closure``: uncertainty along the path, the candidate search, a false closure.

Prose figures (drawn from the INTEL file the intel chapter ships and from
:mod:`slamcourse.slam.loopclosure`):

- ``odometry-uncertainty``: INTEL's first 167 poses by dead reckoning with the 2σ ellipses of
  their marginal position covariance (odometry only, pose 0 fixed);
- ``candidate-gate``: the graph held on reaching pose 166 and the poses that pass the 95 %
  position gate for pose 166;
- ``false-closure``: the INTEL optimum with and without one false closure.

Exercise pictures draw the givens of the code exercises' first examples (for
``loop-candidates``: the circle of 12 poses, the current pose and the poses the gap leaves out,
never which earlier poses pass the gate).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from slamcourse.plots.canvas import BLUE, GREEN, INK, MUTED, ORANGE, PURPLE, Plane
from slamcourse.plots.picture import Figure, Params, Picture, given
from slamcourse.plots.svg import num
from slamcourse.slam import loopclosure as lc
from slamcourse.slam import posegraph as pg
from slamcourse.slam import se2

ODOMETRY_LAST = 166  # the robot's first return to its starting corridor
ELLIPSE_EVERY = 15
GATE_POSE = 166
GAP = 20
CONFIDENCE = 0.95
FALSE_EDGE = (50, 203, 223)  # closure 50 → 203's measurement attached to pose 223
ITERATIONS = 10


@lru_cache(maxsize=1)
def _intel() -> pg.PoseGraph:
    from slamcourse.course.locate import bundled_course_root

    path = bundled_course_root() / "exercises" / "intel" / "data" / "input_INTEL.g2o"
    return pg.parse_g2o(path.read_text(encoding="utf-8"))


def odometry_chain(last: int = ODOMETRY_LAST) -> tuple[np.ndarray, np.ndarray]:
    """INTEL's poses 0 … ``last`` by dead reckoning and their marginal covariances (n×3×3)."""
    graph = _intel()
    chain = [e for e in graph.edges if e.j == e.i + 1 and e.j <= last]
    chain.sort(key=lambda e: e.i)
    poses = [(0.0, 0.0, 0.0)]
    for e in chain:
        poses.append(se2.compose(poses[-1], e.z))
    x = np.array(poses)
    return x, lc.odometry_covariances(x, chain)


@lru_cache(maxsize=1)
def arrival_snapshot(j: int = GATE_POSE) -> lc.Snapshot:
    """The optimised graph held on reaching pose ``j``: poses from 5 before its earliest closure
    partner up to ``j``, every edge among them but the closures at ``j``."""
    graph = _intel()
    closures = [e for e in graph.edges if e.j == j and abs(e.i - e.j) != 1]
    first = max(0, min(e.i for e in closures) - 5)
    return lc.snapshot(graph, first, j, [(e.i, e.j) for e in closures], ITERATIONS)


def gate_candidates(j: int = GATE_POSE) -> tuple[lc.Snapshot, list[int]]:
    """The snapshot at ``j`` and its candidates (global pose ids) at the 95 % χ²₂ gate."""
    snap = arrival_snapshot(j)
    n = len(snap.poses)
    k = n - 1
    marginals = np.array([lc.block(snap.cov, i, i) for i in range(n)])
    cross = np.array([lc.block(snap.cov, i, k) for i in range(n)])
    local = lc.loop_candidates(snap.poses, marginals, cross, GAP, lc.chi2_gate(2, CONFIDENCE))
    return snap, [i + snap.first for i in local]


@lru_cache(maxsize=1)
def false_closure_runs() -> tuple[np.ndarray, np.ndarray]:
    """INTEL's optimum and the optimum with the false closure added, both seen from pose 0."""
    graph = _intel()
    i, j, wrong = FALSE_EDGE
    real = next(e for e in graph.edges if (e.i, e.j) == (i, j))
    false = pg.Edge(i, wrong, real.z, real.information)
    good, _ = pg.gauss_newton(graph.poses, graph.edges, ITERATIONS)
    bad, _ = pg.gauss_newton(graph.poses, [*graph.edges, false], ITERATIONS)
    return pg.relative_to_first(good), pg.relative_to_first(bad)


# --- prose figures ------------------------------------------------------------------------------


def odometry_uncertainty() -> str:
    x, cov = odometry_chain()
    last = len(x) - 1
    shown = [*range(ELLIPSE_EVERY, last, ELLIPSE_EVERY), last]
    pts = [(float(p[0]), float(p[1])) for p in x]
    for k in shown:
        a, _, _ = lc.ellipse(cov[k][:2, :2], 2.0)
        pts += [(x[k, 0] - a, x[k, 1] - a), (x[k, 0] + a, x[k, 1] + a)]
    plane = Plane(pts, width=560, height=440, pad=30, top=50)
    plane.path(pts[: last + 1], colour=INK, width=1.5)
    for k in shown:
        plane.ellipse(float(x[k, 0]), float(x[k, 1]), cov[k][:2, :2], k=2.0, colour=BLUE)
    plane.pose(0.0, 0.0, 0.0, colour=GREEN, label="pose 0 (fixed)")
    plane.point(float(x[19, 0]), float(x[19, 1]), colour=PURPLE, shape="square", label="pose 19")
    plane.pose(
        float(x[last, 0]), float(x[last, 1]), float(x[last, 2]), colour=ORANGE, label=f"pose {last}"
    )
    sd = [lc.ellipse(cov[k][:2, :2], 1.0)[0] for k in shown]
    heading = [math.sqrt(cov[k][2, 2]) for k in shown]
    desc = (
        f"Plan view in metres of INTEL's poses 0 to {last} by dead reckoning, pose 0 fixed at the "
        f"origin, with the 2σ ellipse of each {ELLIPSE_EVERY}th pose's marginal position "
        f"covariance. The largest standard deviation grows from {num(sd[0])} m at pose "
        f"{shown[0]} to {num(sd[-1])} m at pose {last}, and the heading's from "
        f"{num(heading[0])} rad to {num(heading[-1])} rad. Pose {last} is back near pose 19."
    )
    legend = [("dead reckoning", INK, ""), ("2σ position ellipse", BLUE, "")]
    return plane.svg("Odometry-only uncertainty along INTEL's first loop", desc, legend)


def candidate_gate() -> str:
    snap, cands = gate_candidates()
    x = snap.poses
    k = len(x) - 1
    pts = [(float(p[0]), float(p[1])) for p in x]
    plane = Plane(pts, width=560, height=440, pad=34, top=60)
    plane.path(pts, colour=MUTED, width=1.2, dash="3 3")
    for g in cands:
        i = g - snap.first
        plane.point(float(x[i, 0]), float(x[i, 1]), colour=GREEN, shape="circle", size=4.0)
    past = [i for i in range(k - GAP + 1) if i + snap.first not in cands]
    for i in past[::6]:
        plane.point(float(x[i, 0]), float(x[i, 1]), colour=MUTED, shape="cross", size=3.0)
    i19 = 19 - snap.first
    plane.label(float(x[i19, 0]), float(x[i19, 1]), "pose 19", colour=GREEN, bold=True)
    plane.pose(
        float(x[k, 0]),
        float(x[k, 1]),
        float(x[k, 2]),
        colour=ORANGE,
        label=f"pose {GATE_POSE} (now)",
    )
    gate = lc.chi2_gate(2, CONFIDENCE)
    desc = (
        f"Plan view in metres of the graph INTEL's robot holds on reaching pose {GATE_POSE}: "
        f"poses {snap.first} to {GATE_POSE}, odometry only, optimised with pose {snap.first} "
        f"fixed. Earlier poses at least {GAP} steps back whose relative position to pose "
        f"{GATE_POSE} has a squared Mahalanobis distance below {num(gate)} (95 % of χ² with 2 "
        f"degrees of freedom) are candidates: {len(cands)} poses, {cands[0]} to {cands[-1]}, "
        "drawn as filled circles; the others (crosses, every sixth shown) are ruled out."
    )
    legend = [
        ("graph's trajectory", MUTED, "3 3"),
        ("candidate (d² ≤ gate)", GREEN, ""),
        ("ruled out", MUTED, ""),
    ]
    return plane.svg(f"Loop-closure candidates for pose {GATE_POSE}", desc, legend)


def false_closure() -> str:
    good, bad = false_closure_runs()
    i, _, wrong = FALSE_EDGE
    pts = [(float(p[0]), float(p[1])) for p in np.vstack([good, bad])]
    plane = Plane(pts, width=560, height=460, pad=26, top=10)
    plane.path([(float(p[0]), float(p[1])) for p in good], colour=MUTED, width=1.0, every=2)
    plane.path(
        [(float(p[0]), float(p[1])) for p in bad], colour=ORANGE, width=1.0, every=2, dash="4 2"
    )
    start, end = (float(bad[i, 0]), float(bad[i, 1])), (float(bad[wrong, 0]), float(bad[wrong, 1]))
    plane.segment(start, end, colour=PURPLE, width=4.0)
    plane.label(
        float(bad[wrong, 0]),
        float(bad[wrong, 1]),
        f"false closure {i}–{wrong}",
        colour=PURPLE,
        bold=True,
    )
    shift = float(np.max(np.hypot(*(bad[:, :2] - good[:, :2]).T)))
    desc = (
        f"Plan view in metres of INTEL after {ITERATIONS} Gauss-Newton iterations, seen from "
        f"pose 0: the optimum (grey) and the optimum with one false closure between poses {i} "
        f"and {wrong} added (orange, dashed; the false edge is the thick purple line). The "
        f"false edge moves poses by up to {num(shift)} m."
    )
    legend = [
        ("optimum", MUTED, ""),
        ("with one false closure", ORANGE, "4 2"),
        ("the false edge", PURPLE, ""),
    ]
    return plane.svg("What one false loop closure does to INTEL", desc, legend)


# --- exercise pictures (givens only) ------------------------------------------------------------

PAIR_EXAMPLE = (
    (1.0, 2.0, math.pi / 2),
    (1.0, 5.0, math.pi / 2),
    [[0.04, 0.0], [0.0, 0.01]],
    [[0.09, 0.01], [0.01, 0.04]],
)
CLOSURE_EXAMPLE = ((1.0, 2.0, 0.3), (2.2, 3.1, 1.9), (1.5, -0.5, math.pi / 2))


def two_poses(_: Params) -> str:
    xi, xj, ci, cj = PAIR_EXAMPLE
    plane = Plane([(-0.5, 1.0), (2.5, 6.0)], width=420, height=360, pad=30, top=10, grid=1.0)
    plane.ellipse(xi[0], xi[1], ci, k=2.0, colour=BLUE)
    plane.ellipse(xj[0], xj[1], cj, k=2.0, colour=ORANGE)
    plane.segment(xi[:2], xj[:2], colour=MUTED, dash="4 3", arrow=True)
    plane.pose(*xi, colour=BLUE, label="pose i", axes=0.6)
    plane.pose(*xj, colour=ORANGE, label="pose j")
    desc = (
        "Plan view in metres with a 1 m grid: pose i at (1, 2) facing +y and pose j at (1, 5), "
        "3 m straight ahead of it, each with the 2σ ellipse of its marginal position covariance "
        "(0.04 and 0.01 m² for pose i; 0.09, 0.04 m² and a small correlation for pose j). The "
        "exercise's first example; the relative covariance asked for is not drawn."
    )
    legend = [("pose i, 2σ", BLUE, ""), ("pose j, 2σ", ORANGE, "")]
    return plane.svg("Two uncertain poses and their relative pose", desc, legend)


def candidate_closure(_: Params) -> str:
    xi, xj, z = CLOSURE_EXAMPLE
    claimed = se2.compose(xi, z)
    plane = Plane(
        [xi[:2], xj[:2], claimed[:2], (0.5, 1.0), (3.5, 3.8)],
        width=420,
        height=340,
        pad=30,
        top=10,
        grid=1.0,
    )
    plane.pose(*xi, colour=BLUE, label="pose i", axes=0.6)
    plane.pose(*xj, colour=ORANGE, label="pose j (graph)")
    plane.pose(*claimed, colour=PURPLE, label="pose j (claimed by z)", hollow=True)
    plane.segment(xi[:2], (claimed[0], claimed[1]), colour=PURPLE, dash="4 3", arrow=True)
    desc = (
        "Plan view in metres with a 1 m grid: pose i at (1, 2) heading 0.3 rad, pose j where the "
        "graph places it at (2.2, 3.1) heading 1.9 rad, and where the candidate measurement "
        f"z = (1.5, −0.5, π/2) would put it, at ({num(claimed[0])}, {num(claimed[1])}). The "
        "exercise's first example; the NIS asked for is not drawn."
    )
    legend = [("graph's estimate", ORANGE, ""), ("claimed by the closure", PURPLE, "4 3")]
    return plane.svg("A candidate loop closure against the graph", desc, legend)


# the first example of loop-closure/loop-candidates: a circle of 12 poses by odometry, gap 3
SEARCH_EXAMPLE = (
    (0.0, 0.0, 0.0),
    (1.5, 0.0, 0.6),
    (2.738, 0.847, 1.2),
    (3.282, 2.245, 1.8),
    (2.941, 3.706, 2.4),
    (1.835, 4.719, 3.0),
    (0.35, 4.931, -2.683),
    (-0.995, 4.267, -2.083),
    (-1.731, 2.96, -1.483),
    (-1.6, 1.465, -0.883),
    (-0.648, 0.306, -0.283),
    (0.793, -0.113, 0.317),
)
SEARCH_GAP = 3


def search_scene(_: Params) -> str:
    x = SEARCH_EXAMPLE
    k = len(x) - 1
    pts = [(p[0], p[1]) for p in x]
    plane = Plane(pts, width=440, height=400, pad=40, top=40, grid=1.0)
    plane.path(pts, colour=MUTED, width=1.2, dash="3 3", block=True)
    for i, (px, py, _heading) in enumerate(x[:k]):
        searched = i <= k - SEARCH_GAP
        plane.point(
            px,
            py,
            colour=BLUE if searched else MUTED,
            shape="circle" if searched else "cross",
            size=4.0,
            label=str(i),
        )
    plane.pose(*x[k], colour=ORANGE, label=f"pose {k} (now)")
    desc = (
        f"Plan view in metres with a 1 m grid: the exercise's first example, {len(x)} poses "
        "driven by odometry round a circle from pose 0 at the origin, the current pose "
        f"{k} at ({num(x[k][0])}, {num(x[k][1])}), back near poses 0 and 1. With a gap of "
        f"{SEARCH_GAP}, poses 0 to {k - SEARCH_GAP} are searched (circles) and poses "
        f"{k - SEARCH_GAP + 1} to {k - 1} are left out (crosses). Which searched poses pass "
        "the gate is not drawn."
    )
    legend = [
        ("searched (i ≤ k − gap)", BLUE, ""),
        ("left out by the gap", MUTED, ""),
        ("current pose k", ORANGE, ""),
    ]
    return plane.svg("Where could the robot be again?", desc, legend)


FIGURES: dict[str, Figure] = {
    "loop-closure/odometry-uncertainty": odometry_uncertainty,
    "loop-closure/candidate-gate": candidate_gate,
    "loop-closure/false-closure": false_closure,
}

PICTURES: dict[str, Picture] = {
    "loop-closure/relative-covariance": given(two_poses),
    "loop-closure/closure-nis": given(candidate_closure),
    "loop-closure/loop-candidates": given(search_scene),
}
