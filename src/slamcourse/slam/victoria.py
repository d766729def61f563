"""Landmark SLAM on real data: the Victoria Park data set as a landmark pose graph and an EKF.

The data (GTSAM's text version, ``exercises/victoria-park/data/victoria_park.txt``) has two
kinds of lines, in the order the car recorded them:

- ``ODOMETRY i j dx dy dθ c11 c12 c13 c22 c23 c33``: the motion from pose ``i`` to the next pose
  ``j`` in ``i``'s frame (metres, radians) and the upper triangle, row by row, of its 3×3
  **covariance** (not an information matrix);
- ``LANDMARK i l x y c11 c12 c22``: landmark ``l`` seen from pose ``i`` at ``(x, y)`` in the
  robot's frame (metres), with the upper triangle of its 2×2 covariance (m²).

Poses and landmarks share one numbering (GTSAM's keys): ids are unique across both, and pose
ids skip the numbers landmarks took. Here poses are indexed ``0 … n−1`` by increasing id (the
order of the chain) and landmarks ``0 … m−1`` by increasing id.

The measurement model of this course (stated once): a LANDMARK line measures the landmark's
position in the robot's frame,

    h(x_i, l) = R_iᵀ (l − t_i),    e = h(x_i, l) − z,    Ω = Σ⁻¹ (Σ from the line),

linear in the landmark and with Jacobians ``A = ∂e/∂x_i = [−R_iᵀ | (h_y, −h_x)ᵀ]`` (2×3) and
``B = ∂e/∂l = R_iᵀ`` (2×2). Odometry lines are pose-graph edges with the error of
:mod:`slamcourse.slam.posegraph` (``e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)``, information ``Σ⁻¹``).
``χ² = Σ eᵀ Ω e`` over both kinds; Gauss-Newton holds pose 0 fixed.

GTSAM's own reader turns each LANDMARK line into a bearing ``atan2(y, x)`` and a range
``hypot(x, y)`` with ``σ_bearing = √(c11 / 10)`` rad and ``σ_range = √c11`` m
(:func:`gtsam_sigmas`); :func:`range_bearing_terms` implements that reading for comparison.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import ekfslam
from slamcourse.slam import posegraph as pg
from slamcourse.slam.se2 import wrap_angle

Array = NDArray[np.float64]
Index = NDArray[np.intp]
Values = Sequence[float] | NDArray[np.float64]  # a short vector: a list or an array
POSE, POINT = 3, 2


@dataclass(frozen=True)
class LandmarkData:
    """A landmark SLAM problem read from GTSAM's text format.

    ``pose_ids`` and ``landmark_ids`` are the file's ids, increasing; every other array refers
    to poses and landmarks by their index in these tuples. Odometry ``k`` links pose
    ``odometry_from[k]`` to ``odometry_to[k]``; observation ``k`` is landmark ``seen[k]``
    measured from pose ``seen_from[k]``. Lines keep the file's order.
    """

    pose_ids: tuple[int, ...]
    landmark_ids: tuple[int, ...]
    odometry_from: Index
    odometry_to: Index
    odometry: Array  # (M, 3): dx, dy, dθ
    odometry_cov: Array  # (M, 3, 3)
    seen_from: Index
    seen: Index
    measured: Array  # (K, 2): x, y in the robot's frame
    measured_cov: Array  # (K, 2, 2)
    edges: tuple[pg.Edge, ...] = field(default=(), compare=False, repr=False)

    @property
    def n(self) -> int:
        return len(self.pose_ids)

    @property
    def m(self) -> int:
        return len(self.landmark_ids)


def _sym3(c: Sequence[float | str]) -> list[list[float]]:
    c11, c12, c13, c22, c23, c33 = (float(v) for v in c)
    return [[c11, c12, c13], [c12, c22, c23], [c13, c23, c33]]


def parse_victoria(text: str) -> LandmarkData:
    """Read GTSAM's ``ODOMETRY`` / ``LANDMARK`` text (other lines and blank lines skipped)."""
    odo: list[tuple[int, int, list[float], list[list[float]]]] = []
    obs: list[tuple[int, int, list[float], list[list[float]]]] = []
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "ODOMETRY":
            odo.append((int(f[1]), int(f[2]), [float(v) for v in f[3:6]], _sym3(f[6:12])))
        elif f[0] == "LANDMARK":
            c11, c12, c22 = (float(v) for v in f[5:8])
            obs.append((int(f[1]), int(f[2]), [float(f[3]), float(f[4])], [[c11, c12], [c12, c22]]))
    pose_ids = sorted({o[0] for o in odo} | {o[1] for o in odo} | {o[0] for o in obs})
    landmark_ids = sorted({o[1] for o in obs})
    pose_at = {p: k for k, p in enumerate(pose_ids)}
    landmark_at = {p: k for k, p in enumerate(landmark_ids)}
    cov3 = np.array([o[3] for o in odo], dtype=float).reshape(-1, 3, 3)
    frm = np.array([pose_at[o[0]] for o in odo], dtype=np.intp)
    to = np.array([pose_at[o[1]] for o in odo], dtype=np.intp)
    z = np.array([o[2] for o in odo], dtype=float).reshape(-1, 3)
    info = np.linalg.inv(cov3) if len(odo) else cov3
    edges = tuple(
        pg.Edge(int(a), int(b), (float(c[0]), float(c[1]), float(c[2])), om)
        for a, b, c, om in zip(frm, to, z, info, strict=True)
    )
    return LandmarkData(
        pose_ids=tuple(pose_ids),
        landmark_ids=tuple(landmark_ids),
        odometry_from=frm,
        odometry_to=to,
        odometry=z,
        odometry_cov=cov3,
        seen_from=np.array([pose_at[o[0]] for o in obs], dtype=np.intp),
        seen=np.array([landmark_at[o[1]] for o in obs], dtype=np.intp),
        measured=np.array([o[2] for o in obs], dtype=float).reshape(-1, 2),
        measured_cov=np.array([o[3] for o in obs], dtype=float).reshape(-1, 2, 2),
        edges=edges,
    )


# --- the measurement model ------------------------------------------------------------------


def _rt(theta: float) -> Array:
    """``R(θ)ᵀ``."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, s], [-s, c]])


def predict_landmark(pose: Values, landmark: Values) -> Array:
    """``h = R(θ)ᵀ (l − t)``: the landmark in the robot's frame (m), shape (2,)."""
    d = np.array([float(landmark[0]) - float(pose[0]), float(landmark[1]) - float(pose[1])])
    h: Array = _rt(float(pose[2])) @ d
    return h


def landmark_error(pose: Values, landmark: Values, z: Values) -> Array:
    """``e = h(x, l) − z`` (m), shape (2,): zero when the estimate explains the line."""
    e: Array = predict_landmark(pose, landmark) - np.array([float(z[0]), float(z[1])])
    return e


def landmark_jacobians(pose: Values, landmark: Values) -> tuple[Array, Array]:
    """``A = ∂e/∂(x, y, θ)`` (2×3) and ``B = ∂e/∂(l_x, l_y)`` (2×2) of :func:`landmark_error`.

    ``∂h/∂t = −R(θ)ᵀ``, ``∂h/∂l = R(θ)ᵀ`` and ``∂h/∂θ = (dR(θ)ᵀ/dθ)(l − t) = (h_y, −h_x)``.
    """
    rt = _rt(float(pose[2]))
    h = predict_landmark(pose, landmark)
    a = np.zeros((2, 3))
    a[:, :2] = -rt
    a[:, 2] = (h[1], -h[0])
    return a, rt.copy()


def inverse_landmark(pose: Values, z: Values) -> Array:
    """``l = t + R(θ) z``: where a line puts its landmark, seen from ``pose`` (m), shape (2,)."""
    local = np.array([float(z[0]), float(z[1])])
    out: Array = np.array([float(pose[0]), float(pose[1])]) + _rt(float(pose[2])).T @ local
    return out


def gtsam_sigmas(c11: float) -> tuple[float, float]:
    """GTSAM's reading of an isotropic LANDMARK covariance ``c11`` (m²): ``σ_bearing =
    √(c11/10)`` (rad) and ``σ_range = √c11`` (m), ``gtsam/slam/dataset.cpp``."""
    return math.sqrt(c11 / 10.0), math.sqrt(c11)


# --- the initial guess ----------------------------------------------------------------------


def initial_guess(data: LandmarkData) -> tuple[Array, Array]:
    """Dead reckoning and first sightings: poses (n×3) and landmarks (m×2).

    Pose 0 is the origin; each ODOMETRY line, in file order, places its second pose at
    ``x_i ⊕ z``; each landmark is placed by its first LANDMARK line, from that line's pose.
    """
    x = np.zeros((data.n, POSE))
    for i, j, z in zip(data.odometry_from, data.odometry_to, data.odometry, strict=True):
        x[j, :2] = inverse_landmark(x[i], z[:2])
        x[j, 2] = wrap_angle(float(x[i, 2] + z[2]))
    landmarks = np.zeros((data.m, POINT))
    placed = np.zeros(data.m, dtype=bool)
    for i, k, z in zip(data.seen_from, data.seen, data.measured, strict=True):
        if not placed[k]:
            landmarks[k] = inverse_landmark(x[i], z)
            placed[k] = True
    return x, landmarks


# --- errors and Jacobians of all factors at once --------------------------------------------


Terms = tuple[Array, Array, Array]  # errors (K, r), Jacobians (K, r, d), informations (K, r, r)


def xy_terms(x: Array, landmarks: Array, data: LandmarkData) -> Terms:
    """Every LANDMARK factor at once: errors (K×2), Jacobians ``[A | B]`` (K×2×5) and
    informations ``Σ⁻¹`` (K×2×2); the same formulas as :func:`landmark_jacobians`."""
    p = x[data.seen_from]
    c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
    d = landmarks[data.seen] - p[:, :2]
    h = np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], axis=1)
    k = len(p)
    jac = np.zeros((k, 2, 5))
    jac[:, 0, 0], jac[:, 0, 1], jac[:, 1, 0], jac[:, 1, 1] = -c, -s, s, -c
    jac[:, 0, 2], jac[:, 1, 2] = h[:, 1], -h[:, 0]
    jac[:, 0, 3], jac[:, 0, 4], jac[:, 1, 3], jac[:, 1, 4] = c, s, -s, c
    om: Array = np.asarray(np.linalg.inv(data.measured_cov), dtype=np.float64)
    return h - data.measured, jac, om


def range_bearing_terms(x: Array, landmarks: Array, data: LandmarkData) -> Terms:
    """GTSAM's reading of the LANDMARK lines: error ``(bearing, range)`` of the prediction
    minus ``(atan2(y, x), hypot(x, y))``, bearing wrapped, information
    ``diag(1/σ_b², 1/σ_r²)`` from :func:`gtsam_sigmas` (the ``c11`` of each line)."""
    p = x[data.seen_from]
    d = landmarks[data.seen] - p[:, :2]
    q = np.einsum("ki,ki->k", d, d)
    r = np.sqrt(q)
    zb = np.arctan2(data.measured[:, 1], data.measured[:, 0])
    zr = np.hypot(data.measured[:, 0], data.measured[:, 1])
    bearing = np.arctan2(d[:, 1], d[:, 0]) - p[:, 2] - zb
    bearing = np.remainder(bearing + np.pi, 2 * np.pi) - np.pi
    e = np.stack([bearing, r - zr], axis=1)
    k = len(p)
    jac = np.zeros((k, 2, 5))
    jac[:, 0, 0], jac[:, 0, 1], jac[:, 0, 2] = d[:, 1] / q, -d[:, 0] / q, -1.0
    jac[:, 0, 3], jac[:, 0, 4] = -d[:, 1] / q, d[:, 0] / q
    jac[:, 1, 0], jac[:, 1, 1] = -d[:, 0] / r, -d[:, 1] / r
    jac[:, 1, 3], jac[:, 1, 4] = d[:, 0] / r, d[:, 1] / r
    om = np.zeros((k, 2, 2))
    c11 = data.measured_cov[:, 0, 0]
    om[:, 0, 0] = 10.0 / c11
    om[:, 1, 1] = 1.0 / c11
    return e, jac, om


def odometry_terms(x: Array, data: LandmarkData) -> Terms:
    """Every ODOMETRY factor (:func:`slamcourse.slam.posegraph.stacked_errors`): errors (M×3),
    Jacobians ``[A | B]`` (M×3×6) and informations (M×3×3)."""
    if not data.edges:
        return np.zeros((0, 3)), np.zeros((0, 3, 6)), np.zeros((0, 3, 3))
    e, a, b, om = pg.stacked_errors(x, data.edges)
    jac: Array = np.concatenate([a, b], axis=2)
    return e, jac, om


def _quadratic(terms: Terms) -> Array:
    e, _, om = terms
    out: Array = np.einsum("ki,kij,kj->k", e, om, e)
    return out


def observation_chi2(x: Array, landmarks: Array, data: LandmarkData, model: str = "xy") -> Array:
    """``eᵀ Ω e`` of every LANDMARK line (K,), under ``model`` (``"xy"`` or ``"gtsam"``)."""
    terms = (xy_terms if model == "xy" else range_bearing_terms)(x, landmarks, data)
    return _quadratic(terms)


def odometry_chi2(x: Array, data: LandmarkData) -> Array:
    """``eᵀ Ω e`` of every ODOMETRY line (M,)."""
    return _quadratic(odometry_terms(x, data))


def chi2(x: Array, landmarks: Array, data: LandmarkData, model: str = "xy") -> float:
    """``χ² = Σ eᵀ Ω e`` over all ODOMETRY and LANDMARK lines (dimensionless)."""
    return float(odometry_chi2(x, data).sum() + observation_chi2(x, landmarks, data, model).sum())


def degrees_of_freedom(data: LandmarkData) -> int:
    """Error components minus free unknowns: ``3M + 2K − 3(n − 1) − 2m``."""
    return 3 * len(data.odometry) + 2 * len(data.measured) - 3 * (data.n - 1) - 2 * data.m


# --- Gauss-Newton ---------------------------------------------------------------------------


def _columns(data: LandmarkData) -> tuple[Index, Index]:
    """The state columns each factor touches: odometry (M×6) and observations (K×5), in the
    state ``(x_0, …, x_{n−1}, l_0, …, l_{m−1})``."""
    three = np.arange(POSE)
    odo = np.concatenate(
        [3 * data.odometry_from[:, None] + three, 3 * data.odometry_to[:, None] + three], axis=1
    )
    obs = np.concatenate(
        [3 * data.seen_from[:, None] + three, 3 * data.n + 2 * data.seen[:, None] + np.arange(2)],
        axis=1,
    )
    return odo.astype(np.intp), obs.astype(np.intp)


def normal_equations(
    x: Array, landmarks: Array, data: LandmarkData, model: str = "xy"
) -> tuple[object, Array]:
    """``H = Σ Jᵀ Ω J`` (scipy sparse CSC, ``3n + 2m`` square) and ``b = Σ Jᵀ Ω e``."""
    from scipy.sparse import coo_matrix  # type: ignore[import-untyped]

    size = POSE * data.n + POINT * data.m
    g = np.zeros(size)
    rows, cols, values = [], [], []
    obs_terms = (xy_terms if model == "xy" else range_bearing_terms)(x, landmarks, data)
    for idx, (e, jac, om) in zip(_columns(data), (odometry_terms(x, data), obs_terms), strict=True):
        if not len(e):
            continue
        jt_om = np.einsum("kai,kab->kib", jac, om)
        np.add.at(g, idx, np.einsum("kib,kb->ki", jt_om, e))
        width = idx.shape[1]
        rows.append(np.repeat(idx, width, axis=1).ravel())
        cols.append(np.tile(idx, (1, width)).ravel())
        values.append(np.einsum("kib,kbj->kij", jt_om, jac).ravel())
    h = coo_matrix(
        (np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size)
    ).tocsc()
    return h, g


def gauss_newton_step(
    x: Array, landmarks: Array, data: LandmarkData, model: str = "xy"
) -> tuple[Array, Array, float]:
    """One undamped step with pose 0 held fixed: new poses, landmarks and the largest update."""
    from scipy.sparse.linalg import spsolve  # type: ignore[import-untyped]

    h, g = normal_equations(x, landmarks, data, model)
    reduced = h[POSE:, POSE:]  # type: ignore[index]
    delta: Array = np.array(spsolve(reduced, -g[POSE:]), dtype=np.float64).reshape(-1)
    free = POSE * (data.n - 1)
    poses = np.array(x, dtype=float)
    poses[1:] += delta[:free].reshape(-1, POSE)
    poses[:, 2] = np.remainder(poses[:, 2] + np.pi, 2 * np.pi) - np.pi
    poses[poses[:, 2] == -np.pi, 2] = np.pi
    points = np.array(landmarks, dtype=float) + delta[free:].reshape(-1, POINT)
    return poses, points, float(np.max(np.abs(delta))) if delta.size else 0.0


def gauss_newton(
    x: Array, landmarks: Array, data: LandmarkData, iterations: int, model: str = "xy"
) -> tuple[Array, Array, list[float]]:
    """``iterations`` steps from ``(x, landmarks)``; returns both and χ² before and after each."""
    poses, points = np.array(x, dtype=float), np.array(landmarks, dtype=float)
    history = [chi2(poses, points, data, model)]
    for _ in range(int(iterations)):
        poses, points, _ = gauss_newton_step(poses, points, data, model)
        history.append(chi2(poses, points, data, model))
    return poses, points, history


def converge(
    x: Array,
    landmarks: Array,
    data: LandmarkData,
    model: str = "xy",
    tol: float = 1e-9,
    limit: int = 50,
) -> tuple[Array, Array, int]:
    """Gauss-Newton steps until the largest update is below ``tol`` (or ``limit`` steps)."""
    poses, points = np.array(x, dtype=float), np.array(landmarks, dtype=float)
    for step in range(1, limit + 1):
        poses, points, largest = gauss_newton_step(poses, points, data, model)
        if largest < tol:
            return poses, points, step
    return poses, points, limit


def relative_state(x: Array, landmarks: Array) -> Array:
    """The state seen from pose 0, flat: ``x_0⁻¹ ⊕ x_k`` for every pose (θ in (−π, π]), then
    ``R_0ᵀ (l − t_0)`` for every landmark; length ``3n + 2m``. It does not depend on where
    the solution sits in the world (the gauge)."""
    poses = np.asarray(x, dtype=float)
    rel = pg.relative_to_first(poses)
    rt = _rt(float(poses[0, 2]))
    pts = (np.asarray(landmarks, dtype=float) - poses[0, :2]) @ rt.T
    out: Array = np.concatenate([rel.ravel(), pts.ravel()])
    return out


def optimise(text: str, iterations: int) -> Array:
    """Read the text, run ``iterations`` steps from :func:`initial_guess`, and return
    :func:`relative_state`."""
    data = parse_victoria(text)
    x, landmarks = initial_guess(data)
    x, landmarks, _ = gauss_newton(x, landmarks, data, iterations)
    return relative_state(x, landmarks)


def rescaled(data: LandmarkData, odometry: float, landmarks: float) -> LandmarkData:
    """The same lines with every ODOMETRY covariance multiplied by ``odometry`` and every
    LANDMARK covariance by ``landmarks``."""
    cov = data.odometry_cov * odometry
    info = np.linalg.inv(cov) if len(cov) else cov
    edges = tuple(pg.Edge(e.i, e.j, e.z, om) for e, om in zip(data.edges, info, strict=True))
    return replace(data, odometry_cov=cov, measured_cov=data.measured_cov * landmarks, edges=edges)


# --- windows and incremental batches --------------------------------------------------------


def window(text: str, first: int, count: int) -> str:
    """Poses ``first … first+count−1`` of the chain (by increasing id), the ODOMETRY lines
    between them and the LANDMARK lines seen from them, in file order, ids unchanged."""
    chain: set[int] = set()
    for line in text.splitlines():
        f = line.split()
        if f[:1] == ["ODOMETRY"]:
            chain |= {int(f[1]), int(f[2])}
    keep = set(sorted(chain)[first : first + count])
    lines = []
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if (f[0] == "ODOMETRY" and int(f[1]) in keep and int(f[2]) in keep) or (
            f[0] == "LANDMARK" and int(f[1]) in keep
        ):
            lines.append(line)
    return "\n".join(lines) + "\n"


def subproblem(data: LandmarkData, count: int) -> LandmarkData:
    """The first ``count`` poses of the chain with their odometry and their observations (and
    only the landmarks these see, renumbered in the same order)."""
    keep_odo = data.odometry_to < count
    keep_obs = data.seen_from < count
    used = np.unique(data.seen[keep_obs])
    renumber = np.full(data.m, -1, dtype=np.intp)
    renumber[used] = np.arange(len(used))
    return LandmarkData(
        pose_ids=data.pose_ids[:count],
        landmark_ids=tuple(data.landmark_ids[k] for k in used),
        odometry_from=data.odometry_from[keep_odo],
        odometry_to=data.odometry_to[keep_odo],
        odometry=data.odometry[keep_odo],
        odometry_cov=data.odometry_cov[keep_odo],
        seen_from=data.seen_from[keep_obs],
        seen=renumber[data.seen[keep_obs]],
        measured=data.measured[keep_obs],
        measured_cov=data.measured_cov[keep_obs],
        edges=tuple(e for e, k in zip(data.edges, keep_odo, strict=True) if k),
    )


@dataclass(frozen=True)
class Stage:
    """One batch of :func:`incremental`: the poses optimised, the steps taken, χ² before the
    first step and at convergence, and the degrees of freedom."""

    poses: int
    steps: int
    chi2_before: float
    chi2_after: float
    dof: int


def incremental(
    data: LandmarkData, stride: int = 500, tol: float = 1e-9
) -> tuple[Array, Array, list[Stage]]:
    """Optimise the first ``stride`` poses, then the first ``2·stride``, … , then all: each
    batch starts from the previous optimum, with the new poses chained on by odometry from it
    and each new landmark placed at its first sighting; Gauss-Newton runs until the largest
    update is below ``tol``. Returns the poses (n×3), the landmarks (m×2) and the batches."""
    full_x, full_l = initial_guess(data)
    done = 0
    previous = np.zeros(0, dtype=np.intp)
    stages: list[Stage] = []
    counts = [*range(stride, data.n, stride), data.n]
    for count in counts:
        sub = subproblem(data, count)
        used = np.unique(data.seen[data.seen_from < count])
        x, pts = initial_guess(sub)  # the new poses' odometry and the new landmarks' sightings
        if done:
            x[:done] = full_x[:done]
            for i, j, z in zip(sub.odometry_from, sub.odometry_to, sub.odometry, strict=True):
                if j >= done:
                    x[j, :2] = inverse_landmark(x[i], z[:2])
                    x[j, 2] = wrap_angle(float(x[i, 2] + z[2]))
            known = np.isin(used, previous)
            first: dict[int, int] = {}
            for k, lm in enumerate(sub.seen):
                first.setdefault(int(lm), k)
            for lm in range(len(used)):
                if known[lm]:
                    pts[lm] = full_l[used[lm]]
                else:
                    k = first[lm]
                    pts[lm] = inverse_landmark(x[sub.seen_from[k]], sub.measured[k])
        before = chi2(x, pts, sub)
        x, pts, steps = converge(x, pts, sub, tol=tol)
        full_x[:count] = x
        full_l[used] = pts
        previous = used
        done = count
        stages.append(Stage(count, steps, before, chi2(x, pts, sub), degrees_of_freedom(sub)))
    return full_x, full_l, stages


# --- EKF-SLAM on the same lines -------------------------------------------------------------


@dataclass(frozen=True)
class EkfRun:
    """The filter after the last line: the mean ``(x_r, y_r, θ_r, l…)`` with landmarks in the
    order they entered, its covariance, the landmark index of each state pair, the filtered
    pose after each ODOMETRY line (n×3) and the NIS ``νᵀ S⁻¹ ν`` of every update."""

    mean: Array
    cov: Array
    order: tuple[int, ...]
    poses: Array
    nis: Array


def ekf_predict(mean: Array, cov: Array, z: Array, motion_cov: Array) -> None:
    """The EKF prediction for a relative motion ``z`` with covariance ``motion_cov`` (3×3),
    in place: ``x_r ← x_r ⊕ z``, the pose rows and columns of ``P`` by ``G = ∂x'/∂x_r`` and
    the pose block plus ``V Σ_u Vᵀ`` with ``V = ∂x'/∂z = blockdiag(R(θ), 1)``."""
    theta = float(mean[2])
    c, s = math.cos(theta), math.sin(theta)
    g = np.array(
        [[1.0, 0.0, -s * z[0] - c * z[1]], [0.0, 1.0, c * z[0] - s * z[1]], [0.0, 0.0, 1.0]]
    )
    v = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    mean[:2] += (c * z[0] - s * z[1], s * z[0] + c * z[1])
    mean[2] = wrap_angle(theta + float(z[2]))
    cov[:POSE, :] = g @ cov[:POSE, :]
    cov[:, :POSE] = cov[:, :POSE] @ g.T
    cov[:POSE, :POSE] += v @ motion_cov @ v.T


def ekf_update(
    mean: Array, cov: Array, column: int, z: Array, r: Array
) -> tuple[Array, Array, float]:
    """One update with the x-y measurement ``z`` (covariance ``r``) of the landmark whose x
    sits at ``column``: the gain by :func:`slamcourse.slam.ekfslam.kalman_gain`, then
    ``μ⁺ = μ + Kν`` and ``P⁺ = P − K S Kᵀ`` (symmetrised; O(n²) instead of the Joseph form's
    O(n³), the same matrix for the optimal gain). Returns ``μ⁺``, ``P⁺`` and the NIS."""
    a, b = landmark_jacobians(mean[:POSE], mean[column : column + 2])
    h = np.zeros((2, mean.size))
    h[:, :POSE] = a
    h[:, column : column + 2] = b
    nu = z - predict_landmark(mean[:POSE], mean[column : column + 2])
    s = ekfslam.innovation_covariance(cov, h, r)
    k = ekfslam.kalman_gain(cov, h, r)
    new_mean = mean + k @ nu
    new_mean[2] = wrap_angle(float(new_mean[2]))
    new_cov = cov - k @ s @ k.T
    return new_mean, (new_cov + new_cov.T) / 2, float(nu @ np.linalg.solve(s, nu))


def ekf_slam(data: LandmarkData) -> EkfRun:
    """EKF-SLAM over the lines in file order, from pose 0 at the origin with zero covariance:
    predict on every ODOMETRY line, update on a LANDMARK line of a mapped landmark, and
    augment the state (:func:`slamcourse.slam.ekfslam.augment`, the x-y line turned into
    range and bearing with the covariance carried through exactly) on a new one."""
    mean = np.zeros(POSE)
    cov = np.zeros((POSE, POSE))
    column: dict[int, int] = {}
    order: list[int] = []
    poses = np.zeros((data.n, POSE))
    nis: list[float] = []
    events = sorted(
        [(int(j), 0, k) for k, j in enumerate(data.odometry_to)]
        + [(int(i), 1, k) for k, i in enumerate(data.seen_from)]
    )
    for _, kind, k in events:
        if kind == 0:
            ekf_predict(mean, cov, data.odometry[k], data.odometry_cov[k])
            poses[data.odometry_to[k]] = mean[:POSE]
            continue
        lm, z, r = int(data.seen[k]), data.measured[k], data.measured_cov[k]
        if lm in column:
            mean, cov, value = ekf_update(mean, cov, column[lm], z, r)
            nis.append(value)
        else:
            rng, bearing = math.hypot(z[0], z[1]), math.atan2(z[1], z[0])
            jac = np.array([[z[0] / rng, z[1] / rng], [-z[1] / rng**2, z[0] / rng**2]])
            column[lm] = mean.size
            order.append(lm)
            mean, cov = ekfslam.augment(mean, cov, [rng, bearing], jac @ r @ jac.T)
    return EkfRun(mean, cov, tuple(order), poses, np.array(nis))


# --- synthetic scenes in the same format ----------------------------------------------------


def simulate(seed: int, poses: int, landmarks: int, shuffle_ids: bool = False) -> str:
    """A small drive in GTSAM's format: ``poses`` poses of a car-like path, ``landmarks``
    trees, noisy odometry and x-y sightings within 12 m, each line with its own (correlated)
    covariance. Ids are shared by poses and landmarks as in GTSAM's file (a landmark takes the
    next id when first seen); with ``shuffle_ids`` the poses take a random increasing subset of
    the ids and the landmarks the rest, in an order unrelated to when they are first seen."""
    rng = np.random.default_rng(seed)
    truth = [(0.0, 0.0, float(rng.uniform(-math.pi, math.pi)))]
    for _ in range(poses - 1):
        ahead, side = float(rng.uniform(0.4, 1.5)), float(rng.uniform(-0.05, 0.05))
        x0, y0, t0 = truth[-1]
        c, s = math.cos(t0), math.sin(t0)
        turn = float(rng.uniform(-0.35, 0.35))
        truth.append((x0 + c * ahead - s * side, y0 + s * ahead + c * side, wrap_angle(t0 + turn)))
    path = np.array([p[:2] for p in truth])
    centre = path.mean(axis=0)
    spread = float(np.max(np.ptp(path, axis=0))) / 2 + 4.0
    trees = centre + rng.uniform(-spread, spread, size=(landmarks, 2))
    total = poses + landmarks
    if shuffle_ids:
        ids = rng.permutation(total)
        pose_ids = sorted(int(v) for v in ids[:poses])
        tree_ids = [int(v) for v in ids[poses:]]
    lines: list[str] = []
    counter = 0
    pose_id: list[int] = []
    tree_id: dict[int, int] = {}
    for k, t in enumerate(truth):
        if shuffle_ids:
            pose_id.append(pose_ids[k])
        else:
            pose_id.append(counter)
            counter += 1
        if k:
            a = truth[k - 1]
            c, s = math.cos(a[2]), math.sin(a[2])
            d = (t[0] - a[0], t[1] - a[1])
            rel = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1], wrap_angle(t[2] - a[2])])
            sig = rng.uniform([0.01, 0.005, 0.005], [0.05, 0.02, 0.03])
            root = (np.eye(3) + rng.uniform(-0.3, 0.3, size=(3, 3))) @ np.diag(sig)
            cov = root @ root.T
            z = rel + rng.multivariate_normal(np.zeros(3), cov)
            upper = (cov[0, 0], cov[0, 1], cov[0, 2], cov[1, 1], cov[1, 2], cov[2, 2])
            values = (z[0], z[1], wrap_angle(float(z[2])), *upper)
            lines.append(
                f"ODOMETRY {pose_id[k - 1]} {pose_id[k]} " + " ".join(f"{v:.6g}" for v in values)
            )
        c, s = math.cos(t[2]), math.sin(t[2])
        for tree in (int(v) for v in rng.permutation(landmarks)):
            d = trees[tree] - t[:2]
            if math.hypot(d[0], d[1]) > 12.0:
                continue
            if tree not in tree_id:
                if shuffle_ids:
                    tree_id[tree] = tree_ids.pop()
                else:
                    tree_id[tree] = counter
                    counter += 1
            local = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])
            root = (np.eye(2) + rng.uniform(-0.4, 0.4, size=(2, 2))) @ np.diag(
                rng.uniform(0.1, 0.6, size=2)
            )
            cov2 = root @ root.T
            meas = local + rng.multivariate_normal(np.zeros(2), cov2)
            seen = (meas[0], meas[1], cov2[0, 0], cov2[0, 1], cov2[1, 1])
            lines.append(
                f"LANDMARK {pose_id[k]} {tree_id[tree]} " + " ".join(f"{v:.6g}" for v in seen)
            )
    return "\n".join(lines) + "\n"


# --- how the degrees of freedom split between odometry and landmark lines -------------------


def redundancy(x: Array, landmarks: Array, data: LandmarkData) -> tuple[float, float]:
    """The expected χ² of the ODOMETRY lines and of the LANDMARK lines at the optimum ``(x,
    landmarks)``, were every line's covariance right: ``Σ_k (r_k − tr(Ω_k J_k H⁻¹ J_kᵀ))`` over
    each group (the group's redundancy); the two add up to :func:`degrees_of_freedom`.

    Uses the structure of a chain: with pose 0 fixed, ``H = [[T, C], [Cᵀ, D]]`` where ``T``
    (the poses) is block-tridiagonal and ``D`` (the landmarks) small, so the marginal
    covariances the traces need come from the Schur complement ``S = D − Cᵀ T⁻¹ C`` and the
    diagonal blocks of ``T⁻¹`` (one forward and one backward sweep over the chain).
    """
    from scipy.linalg import cho_solve_banded, cholesky_banded  # type: ignore[import-untyped]

    n, m = data.n, data.m
    if np.any(data.odometry_to != data.odometry_from + 1):
        raise ValueError("redundancy() needs the odometry to chain pose k to pose k + 1")
    h, _ = normal_equations(x, landmarks, data)
    size = 3 * (n - 1)
    full = h[3:, 3:].tocsr()  # type: ignore[index]
    t = full[:size, :size]
    c = full[:size, size:].toarray()
    d = full[size:, size:].toarray()
    # T in banded (upper) form, bandwidth 5
    band = np.zeros((6, size))
    tc = t.tocoo()
    upper = tc.col >= tc.row
    band[5 + tc.row[upper] - tc.col[upper], tc.col[upper]] = tc.data[upper]
    chol = cholesky_banded(band)
    y = cho_solve_banded((chol, False), c)  # T⁻¹ C
    s_inv = np.linalg.inv(d - c.T @ y)
    # diagonal 3×3 blocks of T⁻¹ (forward Schur complements, backward sweep)
    blocks = [t[3 * k : 3 * k + 3, 3 * k : 3 * k + 3].toarray() for k in range(n - 1)]
    off = [t[3 * k : 3 * k + 3, 3 * k + 3 : 3 * k + 6].toarray() for k in range(n - 2)]
    delta = [blocks[0]]
    for k in range(1, n - 1):
        delta.append(blocks[k] - off[k - 1].T @ np.linalg.solve(delta[k - 1], off[k - 1]))
    tinv = [np.zeros((3, 3))] * (n - 1)
    tinv[-1] = np.linalg.inv(delta[-1])
    for k in range(n - 3, -1, -1):
        di = np.linalg.inv(delta[k])
        tinv[k] = di + di @ off[k] @ tinv[k + 1] @ off[k].T @ di

    def pose_cov(k: int) -> Array:  # covariance of pose k ≥ 1 (state index k − 1)
        yk = y[3 * (k - 1) : 3 * k]
        out: Array = tinv[k - 1] + yk @ s_inv @ yk.T
        return out

    e, jac, om = xy_terms(x, landmarks, data)
    lev = 0.0
    for k in range(len(e)):
        i, lm = int(data.seen_from[k]), int(data.seen[k])
        cols = slice(2 * lm, 2 * lm + 2)
        cov = np.zeros((5, 5))
        cov[3:, 3:] = s_inv[cols, cols]
        if i > 0:
            cross = -y[3 * (i - 1) : 3 * i] @ s_inv[:, cols]
            cov[:3, :3] = pose_cov(i)
            cov[:3, 3:] = cross
            cov[3:, :3] = cross.T
        lev += float(np.trace(om[k] @ jac[k] @ cov @ jac[k].T))
    unknowns = size + 2 * m
    odometry_leverage = unknowns - lev
    return 3 * len(data.odometry) - odometry_leverage, 2 * len(data.measured) - lev
