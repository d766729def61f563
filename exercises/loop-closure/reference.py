"""Reference answers for chapter ``loop-closure``: proposing loop closures and verifying them.

Conventions (g2o's, as in the pose-graph chapter): an edge ``(i, j, z, Ω)`` measures pose ``j``
from pose ``i``; its error is ``e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)``; ``Σ = H⁻¹`` with the first pose of a
graph fixed; ``Σ_ij`` is the 3×3 block (rows of pose ``i``, columns of pose ``j``). The
mathematics lives in :mod:`slamcourse.slam.loopclosure`; the INTEL graph is the one of the
capstone chapter, read from ``../intel/data``. Functions whose name starts with ``mistake_``
compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import loopclosure as lc
from slamcourse.slam import posegraph as pg
from slamcourse.slam import se2

Matrix = NDArray[np.float64]
Pose = Sequence[float]
DATA = Path(__file__).parent.parent / "intel" / "data" / "input_INTEL.g2o"
ITERATIONS = 10

# arrivals: the robot reaches pose ``j`` and the scan matcher proposes closures to the ``i``s;
# the graph it holds then has every edge among poses ``first … j`` except those closures
ARRIVALS = (166, 201, 241, 291, 315, 414, 528, 637)
# the false closure of the prose: closure (50, 203)'s measurement attached to pose 223 instead
FALSE_CLOSURE = (50, 203, 223)


@lru_cache(maxsize=1)
def intel() -> pg.PoseGraph:
    return pg.parse_g2o(DATA.read_text(encoding="utf-8"))


def closures_at(j: int) -> list[pg.Edge]:
    return [e for e in intel().edges if e.j == j and abs(e.i - e.j) != 1]


@lru_cache(maxsize=16)
def arrival(j: int) -> lc.Snapshot:
    """The optimised graph the robot holds on reaching pose ``j``, before its closures there."""
    closures = closures_at(j)
    first = max(0, min(e.i for e in closures) - 5) if closures else max(0, j - 200)
    return lc.snapshot(intel(), first, j, [(e.i, e.j) for e in closures], ITERATIONS)


@lru_cache(maxsize=1)
def intel_optimum() -> tuple[Matrix, list[float]]:
    graph = intel()
    return pg.gauss_newton(graph.poses, graph.edges, ITERATIONS)


# --- numeric exercises ------------------------------------------------------------------------


def gate(confidence: float) -> float:
    return lc.chi2_gate(3, confidence)


def mistake_gate_two_dof(confidence: float) -> float:
    return lc.chi2_gate(2, confidence)


def mistake_gate_one_dof(confidence: float) -> float:
    return lc.chi2_gate(1, confidence)


def mistake_gate_root(confidence: float) -> float:
    return math.sqrt(lc.chi2_gate(3, confidence))


def _d2(tx: float, ty: float, sxx: float, syy: float, sxy: float) -> float:
    t = np.array([tx, ty])
    return float(t @ np.linalg.solve(np.array([[sxx, sxy], [sxy, syy]]), t))


def mahalanobis_value(
    tx: float, ty: float, sxx: float, syy: float, sxy: float, c: float = 0.0
) -> float:
    return _d2(tx, ty, sxx, syy, sxy)


def mistake_d2_no_correlation(
    tx: float, ty: float, sxx: float, syy: float, sxy: float, c: float = 0.0
) -> float:
    """``x²/σ_x² + y²/σ_y²``: the off-diagonal covariance left out."""
    return tx**2 / sxx + ty**2 / syy


def mistake_d2_euclidean(
    tx: float, ty: float, sxx: float, syy: float, sxy: float, c: float = 0.0
) -> float:
    """The squared distance in metres, not in standard deviations."""
    return tx**2 + ty**2


def mistake_d2_times_covariance(
    tx: float, ty: float, sxx: float, syy: float, sxy: float, c: float = 0.0
) -> float:
    """``tᵀ Σ t``: the covariance used where its inverse belongs."""
    t = np.array([tx, ty])
    return float(t @ np.array([[sxx, sxy], [sxy, syy]]) @ t)


def difference_variance(si: float, sj: float, rho: float) -> float:
    """Variance of ``x_j − x_i`` in 1-D: ``σ_i² + σ_j² − 2 ρ σ_i σ_j``."""
    return si**2 + sj**2 - 2 * rho * si * sj


def mistake_difference_no_cross(si: float, sj: float, rho: float) -> float:
    return si**2 + sj**2


def mistake_difference_cross_added(si: float, sj: float, rho: float) -> float:
    return si**2 + sj**2 + 2 * rho * si * sj


def false_closure_edge() -> pg.Edge:
    i, j, wrong = FALSE_CLOSURE
    real = next(e for e in intel().edges if (e.i, e.j) == (i, j))
    return pg.Edge(i, wrong, real.z, real.information)


@lru_cache(maxsize=1)
def false_closure_run() -> tuple[Matrix, list[float]]:
    graph = intel()
    return pg.gauss_newton(graph.poses, [*graph.edges, false_closure_edge()], ITERATIONS)


def false_closure_chi2() -> float:
    """χ² of INTEL with the false closure added, after 10 Gauss-Newton steps from the file."""
    return false_closure_run()[1][-1]


def mistake_false_closure_chi2_half() -> float:
    return false_closure_chi2() / 2


def mistake_false_closure_without_it() -> float:
    return intel_optimum()[1][-1]


def false_closure_edge_chi2() -> float:
    """``eᵀ Ω e`` of the false edge alone at the distorted optimum."""
    x, _ = false_closure_run()
    f = false_closure_edge()
    e = pg.edge_error(x[f.i], x[f.j], f.z)
    return float(e @ f.information @ e)


def false_closure_shift() -> float:
    """The largest distance (m) a pose moves, seen from pose 0, when the false edge is added."""
    good = pg.relative_to_first(intel_optimum()[0])
    bad = pg.relative_to_first(false_closure_run()[0])
    return float(np.max(np.hypot(*(bad[:, :2] - good[:, :2]).T)))


@lru_cache(maxsize=1)
def false_closure_nis() -> float:
    """NIS of the false edge against the optimised INTEL graph (before it is added)."""
    x, _ = intel_optimum()
    f = false_closure_edge()
    p = lc.joint_covariance(x, intel().edges, f.i, f.j)
    return lc.closure_nis(x[f.i], x[f.j], p[:3, :3], p[:3, 3:], p[3:, 3:], f.z, f.information)


# --- code: relative_pose_covariance -----------------------------------------------------------


def _split(P: Any) -> tuple[Matrix, Matrix, Matrix]:
    """``Σ_ii``, ``Σ_ij``, ``Σ_jj`` of a 6×6 joint covariance."""
    p = np.asarray(P, dtype=float)
    return p[:3, :3], p[:3, 3:], p[3:, 3:]


def relative_pose_covariance(xi: Pose, xj: Pose, P: Any) -> Matrix:
    return lc.relative_pose_covariance(xi, xj, *_split(P))


def mistake_relcov_no_cross(xi: Pose, xj: Pose, P: Any) -> Matrix:
    """The cross-covariance ``Σ_ij`` left out: the poses treated as independent."""
    a, _, b = _split(P)
    return lc.relative_pose_covariance(xi, xj, a, np.zeros((3, 3)), b)


def mistake_relcov_world_difference(xi: Pose, xj: Pose, P: Any) -> Matrix:
    """``Σ_ii + Σ_jj − Σ_ij − Σ_ijᵀ``: the covariance of ``x_j − x_i`` in the world frame."""
    a, c, b = _split(P)
    return np.asarray(a + b - c - c.T)


def mistake_relcov_no_lever_arm(xi: Pose, xj: Pose, P: Any) -> Matrix:
    """``J_i`` without the column ``(dR_iᵀ/dθ)(t_j − t_i)``: turning pose ``i`` moves nothing."""
    ji, jj = lc.relative_jacobians(xi, xj)
    ji[:2, 2] = 0.0
    j = np.hstack([ji, jj])
    return np.asarray(j @ np.asarray(P, dtype=float) @ j.T)


# --- code: closure_nis ------------------------------------------------------------------------


def closure_nis(xi: Pose, xj: Pose, P: Any, z: Pose, info: Any) -> float:
    return lc.closure_nis(xi, xj, *_split(P), z, info)


def mistake_nis_edge_only(xi: Pose, xj: Pose, P: Any, z: Pose, info: Any) -> float:
    """``eᵀ Ω e``: the edge's own χ², as if the graph's poses were certain."""
    e = pg.edge_error(xi, xj, z)
    return float(e @ np.asarray(info, dtype=float) @ e)


def mistake_nis_no_measurement_noise(xi: Pose, xj: Pose, P: Any, z: Pose, info: Any) -> float:
    """``S = J Σ Jᵀ`` alone: the closure's own noise ``Ω⁻¹`` left out."""
    e = pg.edge_error(xi, xj, z)
    a, b = pg.edge_jacobians(xi, xj, z)
    j = np.hstack([a, b])
    return float(e @ np.linalg.solve(j @ np.asarray(P, dtype=float) @ j.T, e))


def mistake_nis_no_cross(xi: Pose, xj: Pose, P: Any, z: Pose, info: Any) -> float:
    """The cross-covariance ``Σ_ij`` left out of ``S``."""
    a, _, b = _split(P)
    return lc.closure_nis(xi, xj, a, np.zeros((3, 3)), b, z, info)


def mistake_nis_information_added(xi: Pose, xj: Pose, P: Any, z: Pose, info: Any) -> float:
    """``S = J Σ Jᵀ + Ω``: the information matrix added as if it were a covariance."""
    e = pg.edge_error(xi, xj, z)
    a, b = pg.edge_jacobians(xi, xj, z)
    j = np.hstack([a, b])
    s = j @ np.asarray(P, dtype=float) @ j.T + np.asarray(info, dtype=float)
    return float(e @ np.linalg.solve(s, e))


# --- strategies: inputs from the real building and synthetic ones ----------------------------


def _blocks(snap: lc.Snapshot, i: int, j: int) -> dict[str, Any]:
    a, b = snap.local(i), snap.local(j)
    p = lc.joint(lc.block(snap.cov, a, a), lc.block(snap.cov, a, b), lc.block(snap.cov, b, b))
    return {"xi": snap.poses[a].tolist(), "xj": snap.poses[b].tolist(), "P": p.tolist()}


@lru_cache(maxsize=1)
def intel_pairs() -> list[dict[str, Any]]:
    """Pose pairs of the real building: each closure proposed on arrival, with the blocks of
    the graph the robot held then, and a neighbour of it a few poses back."""
    out = []
    for j in ARRIVALS:
        snap = arrival(j)
        for e in closures_at(j):
            out.append(_blocks(snap, e.i, j))
        out.append(_blocks(snap, j - 3, j))
    return out


@lru_cache(maxsize=1)
def intel_closures() -> list[dict[str, Any]]:
    """Candidate closures in the real building, tested against the graph held on arrival: every
    true closure proposed there, and the same measurement attached to a wrong pose (8 or 25
    poses later along the old path: a false positive of the place recogniser)."""
    out = []
    for j in ARRIVALS:
        snap = arrival(j)
        for e in closures_at(j):
            meas = {"z": list(e.z), "info": e.information.tolist()}
            out.append({**_blocks(snap, e.i, j), **meas})
            for shift in (8, 25):
                if snap.local(e.i + shift) < snap.local(j) - 5:
                    out.append({**_blocks(snap, e.i + shift, j), **meas})
    return out


def _joint(seed: int) -> Matrix:
    """A realistic 6×6 joint covariance: standard deviations 1 cm – 2 m and 0.005 – 0.5 rad,
    with correlations between and within the poses."""
    rng = np.random.default_rng(seed)
    sxy, st = rng.uniform(0.01, 2.0), rng.uniform(0.005, 0.5)
    d = np.diag([sxy, sxy, st] * 2) * rng.uniform(0.5, 1.5, size=6)
    m = rng.uniform(-1.0, 1.0, size=(6, 6))
    corr = m @ m.T + 0.05 * np.eye(6)
    corr /= np.sqrt(np.outer(np.diag(corr), np.diag(corr)))
    out = d @ corr @ d
    return np.asarray(np.vectorize(lambda v: float(f"{v:.12g}"))((out + out.T) / 2))


def _information(seed: int) -> Matrix:
    """A closure's information: standard deviations 2 cm – 0.5 m and 0.01 – 0.2 rad, correlated."""
    rng = np.random.default_rng(seed + 1)
    scale = np.diag(
        [1 / rng.uniform(0.02, 0.5), 1 / rng.uniform(0.02, 0.5), 1 / rng.uniform(0.01, 0.2)]
    )
    root = (np.eye(3) + rng.uniform(-0.4, 0.4, size=(3, 3))) @ scale
    out = root.T @ root
    return np.asarray(np.vectorize(lambda v: float(f"{v:.12g}"))((out + out.T) / 2))


def _synthetic_pair(seed: int, xi: Pose, xj: Pose) -> dict[str, Any]:
    return {"xi": list(xi), "xj": list(xj), "P": _joint(seed).tolist()}


def _pose(span: float) -> Any:
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    return st.tuples(real(-span, span), real(-span, span), real(-math.pi, math.pi))


def pair_inputs() -> Any:
    """INTEL pose pairs with their blocks, and synthetic poses in [−30, 30] m with a random
    realistic joint covariance."""
    from hypothesis import strategies as st

    made = st.builds(_synthetic_pair, st.integers(0, 2**32 - 1), _pose(30.0), _pose(30.0))
    return st.one_of(st.sampled_from(intel_pairs()), made)


def closure_inputs() -> Any:
    """INTEL candidate closures (true and false), and synthetic ones: two poses in [−30, 30] m
    with a realistic joint covariance, a measurement near or far from their relative pose."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    def build(seed: int, xi: Pose, dz: Pose, noise: Pose) -> dict[str, Any]:
        xj = se2.compose(xi, dz)
        z = se2.compose(dz, noise)
        return {
            **_synthetic_pair(seed, xi, [round(v, 9) for v in xj]),
            "z": [round(v, 9) for v in z],
            "info": _information(seed).tolist(),
        }

    small = st.tuples(real(-1.0, 1.0), real(-1.0, 1.0), real(-0.5, 0.5))
    made = st.builds(build, st.integers(0, 2**32 - 1), _pose(25.0), _pose(3.0), small)
    return st.one_of(st.sampled_from(intel_closures()), made)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def _pose_ok(p: Any, span: float) -> bool:
    try:
        a = np.asarray(p, dtype=float)
    except (TypeError, ValueError):
        return False
    return a.shape == (3,) and bool(np.all(np.abs(a[:2]) <= span)) and abs(a[2]) <= math.pi


def _joint_ok(P: Any) -> bool:
    try:
        s = np.asarray(P, dtype=float)
    except (TypeError, ValueError):
        return False
    if s.shape != (6, 6) or not np.allclose(s, s.T, rtol=0, atol=1e-12 * np.abs(s).max()):
        return False
    w = np.linalg.eigvalsh(s)
    return bool(w[-1] > 0 and w[0] >= -1e-9 * w[-1])


def pair_valid(xi: Any, xj: Any, P: Any) -> bool:
    """Poses with positions in [−50, 50] m and headings in [−π, π]; a symmetric positive
    semidefinite 6×6 joint covariance."""
    return _pose_ok(xi, 50) and _pose_ok(xj, 50) and _joint_ok(P)


def closure_valid(xi: Any, xj: Any, P: Any, z: Any, info: Any) -> bool:
    """As ``pair_valid``, with a measurement within 5 m and a positive-definite information
    whose innovation covariance is well conditioned (NIS defined to many digits)."""
    if not (pair_valid(xi, xj, P) and _pose_ok(z, 5)):
        return False
    om = np.asarray(info, dtype=float)
    if om.shape != (3, 3) or not np.allclose(om, om.T, rtol=0, atol=1e-12 * np.abs(om).max()):
        return False
    if np.linalg.eigvalsh(om)[0] <= 0:
        return False
    e = pg.edge_error(xi, xj, z)
    if abs(abs(float(e[2])) - math.pi) < 1e-9:  # an innovation of exactly ±π has no one sign
        return False
    s = lc.innovation_covariance(xi, xj, *_split(P), z, om)
    return bool(np.linalg.cond(s) < 1e9)


# --- code: loop_candidates --------------------------------------------------------------------

# the INTEL inputs: the graph held on each arrival, its last WINDOW poses searched for the
# arrival pose, with the gap and confidence of that input
WINDOW = 200
ARRIVAL_SEARCH = {
    166: (10, 0.99),
    201: (20, 0.95),
    241: (15, 0.9),
    291: (20, 0.95),
    315: (25, 0.99),
    414: (20, 0.95),
    528: (30, 0.95),
    637: (5, 0.999),
}


def _stacks(marginals: Any, cross: Any) -> tuple[Matrix, Matrix]:
    return np.asarray(marginals, dtype=float), np.asarray(cross, dtype=float)


def loop_candidates(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """The poses ``i ≤ k − gap`` (``k`` the last) whose relative position to ``k`` passes the
    ``χ²₂`` gate at ``confidence``, in increasing order."""
    m, c = _stacks(marginals, cross)
    return lc.loop_candidates(poses, m, c, gap, lc.chi2_gate(2, confidence))


def _relative(poses: Any, marginals: Any, cross: Any, i: int) -> tuple[Matrix, Matrix]:
    """``r = x_i⁻¹ ⊕ x_k`` (angle wrapped) and its 3×3 covariance ``Σ_r``."""
    x = np.asarray(poses, dtype=float)
    m, c = _stacks(marginals, cross)
    k = len(x) - 1
    r = np.array(se2.between(x[i], x[k]))
    r[2] = se2.wrap_angle(float(r[2]))
    return r, lc.relative_pose_covariance(x[i], x[k], m[i], c[i], m[k])


def _window(poses: Any, gap: int) -> range:
    return range(0, len(poses) - int(gap))


def mistake_cand_no_cross(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """``Σ_ik`` left out: the two poses treated as independent."""
    m, c = _stacks(marginals, cross)
    k = len(m) - 1
    zero = np.zeros_like(c)
    zero[k] = c[k]  # Σ_kk stays: only the cross-covariances go
    return lc.loop_candidates(poses, m, zero, gap, lc.chi2_gate(2, confidence))


def mistake_cand_pose_k_alone(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """The world offset ``t_k − t_i`` gated with the current pose's own marginal ``Σ_kk``."""
    x = np.asarray(poses, dtype=float)
    m, _ = _stacks(marginals, cross)
    k = len(x) - 1
    gate = lc.chi2_gate(2, confidence)
    out = []
    for i in _window(x, gap):
        w = x[k, :2] - x[i, :2]
        if float(w @ np.linalg.solve(m[k][:2, :2], w)) <= gate:
            out.append(i)
    return out


def mistake_cand_euclidean(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """The squared distance in metres compared with the gate."""
    x = np.asarray(poses, dtype=float)
    gate = lc.chi2_gate(2, confidence)
    k = len(x) - 1
    return [i for i in _window(x, gap) if float(np.sum((x[k, :2] - x[i, :2]) ** 2)) <= gate]


def mistake_cand_full_pose(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """The whole relative pose, heading included, gated with ``χ²₃``."""
    gate = lc.chi2_gate(3, confidence)
    out = []
    for i in _window(poses, gap):
        r, s = _relative(poses, marginals, cross, i)
        if float(r @ np.linalg.solve(s, r)) <= gate:
            out.append(i)
    return out


def mistake_cand_three_dof_quantile(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """The position's ``d²`` (2 degrees of freedom) against the ``χ²₃`` quantile."""
    m, c = _stacks(marginals, cross)
    return lc.loop_candidates(poses, m, c, gap, lc.chi2_gate(3, confidence))


def mistake_cand_sorted_by_distance(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """The right candidates, most likely first (by ``d²``) instead of by index."""
    m, c = _stacks(marginals, cross)
    d2 = lc.candidate_distances(poses, m, c, gap)
    gate = lc.chi2_gate(2, confidence)
    return sorted((i for i, v in d2.items() if v <= gate), key=lambda i: d2[i])


def mistake_cand_no_gap(
    poses: Any, marginals: Any, cross: Any, gap: int, confidence: float
) -> list[int]:
    """Every earlier pose searched: the most recent ones not left out."""
    m, c = _stacks(marginals, cross)
    return lc.loop_candidates(poses, m, c, 1, lc.chi2_gate(2, confidence))


def _rounded(a: Any) -> Any:
    return np.vectorize(lambda v: float(f"{v:.12g}"))(np.asarray(a, dtype=float)).tolist()


def _search_input(
    poses: Matrix, cov: Matrix, lo: int, gap: int, confidence: float
) -> dict[str, Any]:
    """The search for the last pose of ``poses[lo:]``, with the blocks of ``cov`` (``H⁻¹``)."""
    k = len(poses) - 1
    keep = range(lo, k + 1)
    return {
        "poses": _rounded(poses[lo:]),
        "marginals": _rounded([lc.block(cov, i, i) for i in keep]),
        "cross": _rounded([lc.block(cov, i, k) for i in keep]),
        "gap": gap,
        "confidence": confidence,
    }


@lru_cache(maxsize=1)
def intel_searches() -> list[dict[str, Any]]:
    """The candidate search on each arrival of INTEL's robot: the graph it held on reaching the
    pose (before the closures found there), its last ``WINDOW`` poses searched."""
    out = []
    for j, (gap, confidence) in ARRIVAL_SEARCH.items():
        snap = arrival(j)
        lo = max(0, len(snap.poses) - WINDOW)
        out.append(_search_input(snap.poses, snap.cov, lo, gap, confidence))
    return out


def _graph_search(
    seed: int, n: int, loops: int, sxy: float, sth: float, gap: int, confidence: float
) -> dict[str, Any]:
    """A synthetic graph (a random walk of ``n`` poses, odometry and ``loops`` closures with the
    given noise) and the search for its last pose, with the blocks of its ``H⁻¹``."""
    x, edges = pg.simulate(seed, n, loops, noise=(sxy, sth))
    return _search_input(x, lc.covariance(x, edges), 0, gap, confidence)


def _loop_search(
    seed: int,
    n: int,
    miss: float,
    radius: float,
    sxy: float,
    sth: float,
    loops: int,
    gap: int,
    confidence: float,
) -> dict[str, Any]:
    """A robot driving once round a circle of ``radius`` metres in ``n`` poses, ending ``miss``
    steps short of its start (negative: past it), by noisy odometry with ``loops`` closures
    among its earlier poses; the search for its last pose."""
    rng = np.random.default_rng(seed)
    turn = 2 * math.pi / (n - 1 + miss)
    length = 2 * radius * math.sin(turn / 2)
    truth = [(0.0, 0.0, 0.0)]
    for _ in range(n - 1):
        step = (length * rng.uniform(0.9, 1.1), rng.normal(0, 0.05 * length), turn)
        truth.append(se2.compose(truth[-1], (step[0], step[1], step[2] + rng.normal(0, 0.03))))
    pairs = [(k, k + 1) for k in range(n - 1)]
    for _ in range(loops):
        i = int(rng.integers(0, n - 3))
        pairs.append((i, int(rng.integers(i + 2, n - 1))))
    edges = []
    for i, j in pairs:
        z = se2.between(truth[i], truth[j])
        z = (
            z[0] + rng.normal(0, sxy),
            z[1] + rng.normal(0, sxy),
            se2.wrap_angle(z[2] + rng.normal(0, sth)),
        )
        root = (np.eye(3) + rng.uniform(-0.3, 0.3, (3, 3))) @ np.diag([1 / sxy, 1 / sxy, 1 / sth])
        edges.append(pg.Edge(i, j, z, root.T @ root))
    guess = [(rng.uniform(-15, 15), rng.uniform(-15, 15), rng.uniform(-math.pi, math.pi))]
    for e in edges[: n - 1]:
        guess.append(se2.compose(guess[-1], e.z))
    x = np.array(guess, dtype=float)
    return _search_input(x, lc.covariance(x, edges), 0, gap, confidence)


def search_inputs() -> Any:
    """INTEL's arrivals; synthetic robots that drive once round a circle and stop up to one
    step short of their start or past it (6 to 40 poses, radius 1.5 – 12 m, noise 2 cm –
    0.3 m and 0.005 – 0.08 rad per edge, up to 2 closures); random walks of 2 to 40 poses;
    gaps of 1 to 12, confidences 0.5 to 0.999."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    confidence = st.one_of(st.sampled_from([0.9, 0.95, 0.99]), real(0.5, 0.999))
    seed = st.integers(0, 2**32 - 1)
    sxy, sth = real(0.02, 0.3), real(0.005, 0.08)
    circle = st.builds(
        _loop_search,
        seed,
        st.integers(6, 40),
        real(-1.0, 1.0),
        real(1.5, 12.0),
        sxy,
        sth,
        st.integers(0, 2),
        st.integers(1, 12),
        confidence,
    )
    walk = st.builds(
        _graph_search,
        seed,
        st.integers(2, 40),
        st.integers(0, 3),
        sxy,
        sth,
        st.integers(1, 12),
        confidence,
    )
    made = st.one_of(circle, circle, walk).filter(lambda kw: search_valid(**kw))
    return st.one_of(st.sampled_from(intel_searches()), made)


def search_valid(poses: Any, marginals: Any, cross: Any, gap: Any, confidence: Any) -> bool:
    """2 to 300 poses with positions in [−50, 50] m and headings in [−π, π]; the blocks of a
    covariance (``Σ_ii`` symmetric, ``cross[k] = Σ_kk``); every searched pose's relative
    position covariance well conditioned, and no ``d²`` within 10⁻⁶ (relative) of the gate,
    where methods may round either way."""
    try:
        x = np.asarray(poses, dtype=float)
        m, c = _stacks(marginals, cross)
    except (TypeError, ValueError):
        return False
    n = len(x)
    if x.shape != (n, 3) or not 2 <= n <= 300 or m.shape != (n, 3, 3) or c.shape != (n, 3, 3):
        return False
    if not (np.isfinite(x).all() and np.isfinite(m).all() and np.isfinite(c).all()):
        return False
    if np.abs(x[:, :2]).max() > 50 or np.abs(x[:, 2]).max() > math.pi:
        return False
    if not np.allclose(m, np.transpose(m, (0, 2, 1)), rtol=1e-9, atol=1e-15):
        return False
    if not np.allclose(c[-1], m[-1], rtol=1e-9, atol=1e-15):
        return False
    if not (isinstance(gap, int | np.integer) and 1 <= gap <= 40 and 0.5 <= confidence <= 0.999):
        return False
    gate = lc.chi2_gate(2, confidence)
    idx, r, s = lc.relative_positions(x, m, c, gap)
    if len(idx) == 0:
        return True
    if np.linalg.eigvalsh(s)[:, 0].min() <= 0 or np.linalg.cond(s).max() > 1e9:
        return False
    d2 = np.einsum("na,na->n", r, np.linalg.solve(s, r[:, :, None])[:, :, 0])
    return not bool(np.any(np.abs(d2 - gate) <= 1e-6 * gate))
