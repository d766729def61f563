"""Reference answers for chapter ``se3``: rotations, SE(3), right perturbations, a 3-D pose graph.

The mathematics lives in :mod:`slamcourse.slam.se3`; the 3-D pose graph ``sphere2500`` (and its
noise-free twin) ships in ``data/`` (attribution in ``data/SOURCE.md``). Functions whose name
starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import se3

Array = NDArray[np.float64]
DATA = Path(__file__).resolve().parent / "data"
SPHERE = DATA / "sphere2500.txt"
TRUTH = DATA / "sphere2500_groundtruth.txt"
WHOLE_ITERATIONS = 10


@lru_cache(maxsize=1)
def sphere_text() -> str:
    return SPHERE.read_text(encoding="utf-8")


@lru_cache(maxsize=1)
def sphere() -> se3.Graph3:
    return se3.parse_edge3(sphere_text())


@lru_cache(maxsize=1)
def truth() -> se3.Graph3:
    """The noise-free edges; composing their odometry gives the true poses."""
    return se3.parse_edge3(TRUTH.read_text(encoding="utf-8"))


def _sqrt_numbers() -> Array:
    """The 21 square-root-information numbers of sphere2500's first edge."""
    first = next(line for line in sphere_text().splitlines() if line.startswith("EDGE3"))
    return np.array([float(v) for v in first.split()[9:30]])


# --- numeric exercises ------------------------------------------------------------------------


def rotation_angle(theta: float, tr: float) -> float:
    """The angle of a rotation matrix with trace ``tr``: ``tr = 1 + 2 cos θ``."""
    return math.acos((tr - 1) / 2)


def mistake_angle_planar(theta: float, tr: float) -> float:
    """The planar habit: ``tr = 2 cos θ``."""
    return math.acos(tr / 2)


def mistake_angle_degrees(theta: float, tr: float) -> float:
    return math.degrees(rotation_angle(theta, tr))


def rotated_point(wx: float, wy: float, wz: float, px: float, py: float, pz: float) -> Array:
    """``Exp(w) p``: the point ``p`` rotated by the rotation vector ``w``."""
    return se3.so3_exp([wx, wy, wz]) @ np.array([px, py, pz])


def mistake_rotated_first_order(
    wx: float, wy: float, wz: float, px: float, py: float, pz: float
) -> Array:
    """``p + w × p``: only the first-order term of the exponential."""
    p = np.array([px, py, pz])
    return p + np.cross([wx, wy, wz], p)


def mistake_rotated_euler(
    wx: float, wy: float, wz: float, px: float, py: float, pz: float
) -> Array:
    """The rotation vector read as roll, pitch, yaw: ``Rz(wz) Ry(wy) Rx(wx) p``."""
    return se3.rpy_matrix(wx, wy, wz) @ np.array([px, py, pz])


def mistake_rotated_inverse(
    wx: float, wy: float, wz: float, px: float, py: float, pz: float
) -> Array:
    return se3.so3_exp([-wx, -wy, -wz]) @ np.array([px, py, pz])


def _left_case(yaw: float, tx: float, ty: float, tz: float) -> tuple[Array, Array]:
    x = se3.pose(se3.rpy_matrix(0.0, 0.0, yaw), [tx, ty, tz])
    delta_world = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.1])
    return x, delta_world


def right_from_left(yaw: float, tx: float, ty: float, tz: float) -> Array:
    """``δ_R = Ad(X⁻¹) δ_L``: the body-frame twin of the world-frame ``δ_L = (0,0,0, 0,0,0.1)``,
    so that ``Exp(δ_L) X = X Exp(δ_R)``."""
    x, d = _left_case(yaw, tx, ty, tz)
    return se3.adjoint(se3.inverse(x)) @ d


def mistake_right_ad_forward(yaw: float, tx: float, ty: float, tz: float) -> Array:
    x, d = _left_case(yaw, tx, ty, tz)
    return se3.adjoint(x) @ d


def mistake_right_same(yaw: float, tx: float, ty: float, tz: float) -> Array:
    """The frames ignored: ``δ_R = δ_L``."""
    return _left_case(yaw, tx, ty, tz)[1]


def yaw_sigma() -> float:
    """σ of the yaw noise that sphere2500's numbers state: ``S₆₆ = 1/σ`` (square-root
    information, the iSAM convention)."""
    return 1 / float(_sqrt_numbers()[-1])


def mistake_yaw_sigma_information() -> float:
    """The number read as information ``1/σ²``."""
    return 1 / math.sqrt(float(_sqrt_numbers()[-1]))


def sphere_dof() -> int:
    """Error components minus free unknowns: ``6·edges − 6·(poses − 1)``."""
    graph = sphere()
    return 6 * len(graph.i) - 6 * (len(graph.poses) - 1)


def mistake_dof_gauge_ignored() -> int:
    graph = sphere()
    return 6 * len(graph.i) - 6 * len(graph.poses)


def mistake_dof_planar() -> int:
    graph = sphere()
    return 3 * len(graph.i) - 3 * (len(graph.poses) - 1)


def sphere_optimum() -> tuple[Array, float]:
    """sphere2500 after ten Gauss-Newton steps from its odometry: poses and χ²."""
    x, history = se3.optimise_text(sphere_text(), WHOLE_ITERATIONS)
    return x, history[-1]


def sphere_chi2() -> float:
    return sphere_optimum()[1]


def mistake_sphere_chi2_half() -> float:
    return sphere_chi2() / 2


@lru_cache(maxsize=1)
def mistake_sphere_chi2_information() -> float:
    """The optimum's χ² when the 21 numbers are taken for Ω itself (GTSAM's reading)."""
    graph = _as_information(sphere())
    _, history = se3.gauss_newton(graph.poses, graph, WHOLE_ITERATIONS)
    return history[-1]


def sphere_ate() -> float:
    """RMS position error (m) of the optimum against the ground truth, after the best rigid
    alignment."""
    x, _ = sphere_optimum()
    return se3.ate_rmse(se3.positions_from_first(x), se3.positions_from_first(truth().poses))


def odometry_ate() -> float:
    """The same for the initial guess (composed odometry)."""
    return se3.ate_rmse(
        se3.positions_from_first(sphere().poses), se3.positions_from_first(truth().poses)
    )


# --- code: so3_log ------------------------------------------------------------------------------


def so3_log(R: Any) -> Array:
    """The rotation vector of a rotation matrix (``|w| ∈ [0, π]``; at exactly π the one whose
    largest-magnitude component is positive)."""
    return se3.so3_log(np.asarray(R, dtype=float))


def _rotation(axis: tuple[float, float, float], theta: float) -> list[list[float]]:
    n = np.asarray(axis, dtype=float)
    out: list[list[float]] = se3.so3_exp(theta * n / np.linalg.norm(n)).tolist()
    return out


def _half_turn(axis: tuple[float, float, float]) -> list[list[float]]:
    """``2 n nᵀ − I``: the rotation by exactly π about ``n``, symmetric in floating point."""
    n = np.asarray(axis, dtype=float)
    n = n / np.linalg.norm(n)
    out: list[list[float]] = (2 * np.outer(n, n) - np.eye(3)).tolist()
    return out


def rotation_inputs() -> Any:
    """Rotation matrices of every angle: uniform in [0, π], tiny (1e-9 to 1e-2 rad), just under
    π (π − 1e-12 to π − 0.1) and exactly π (symmetric matrices), about random axes."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    axis = st.tuples(real(-1, 1), real(-1, 1), real(-1, 1)).filter(lambda v: math.hypot(*v) > 0.1)
    general = st.builds(_rotation, axis, real(0.0, math.pi))
    tiny = st.builds(lambda a, u: _rotation(a, 10.0**u), axis, real(-9, -2))
    near = st.builds(lambda a, u: _rotation(a, math.pi - 10.0**u), axis, real(-12, -1))
    half = st.builds(_half_turn, axis).filter(_clear_largest)
    return st.fixed_dictionaries({"R": st.one_of(general, tiny, near, half)})


def _clear_largest(r: list[list[float]]) -> bool:
    """At exactly π, the convention needs one component of the axis clearly the largest."""
    diag = sorted(np.diag(np.asarray(r, dtype=float)))
    return diag[2] - diag[1] > 1e-6


def rotation_valid(R: Any) -> bool:
    """A rotation matrix (orthonormal to 1e-9, determinant +1); if symmetric and not the
    identity (a half turn), its axis has one clearly largest component."""
    try:
        m = np.asarray(R, dtype=float)
    except (TypeError, ValueError):
        return False
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        return False
    if np.max(np.abs(m.T @ m - np.eye(3))) > 1e-9 or np.linalg.det(m) < 0.5:
        return False
    if np.array_equal(m, m.T) and not np.array_equal(m, np.eye(3)):
        return _clear_largest(m.tolist())
    return True


def mistake_log_acos(R: Any) -> Array:
    """``θ = acos((tr R − 1)/2)``, the axis from the antisymmetric part over ``2 sin θ``, and
    zero below 1e-10: loses the small angles, and the axis near π."""
    m = np.asarray(R, dtype=float)
    theta = math.acos(max(-1.0, min(1.0, (np.trace(m) - 1) / 2)))
    if theta < 1e-10:
        return np.zeros(3)
    return theta / (2 * math.sin(theta)) * 2 * se3.vee(m)


def mistake_log_sin_not_theta(R: Any) -> Array:
    """The antisymmetric part taken for the rotation vector: ``sin θ · n`` instead of ``θ n``."""
    return se3.vee(np.asarray(R, dtype=float))


def mistake_log_transposed(R: Any) -> Array:
    """``vee(Rᵀ − R)``: the inverse rotation's vector."""
    return -so3_log(R)


def mistake_log_unsigned_near_pi(R: Any) -> Array:
    """Near π, the axis from the symmetric part but its sign never checked against the
    antisymmetric part (so always the exactly-π convention)."""
    m = np.asarray(R, dtype=float)
    w = so3_log(m)
    theta = float(np.linalg.norm(w))
    if theta > math.pi - se3.NEAR_PI:
        return so3_log(_half_turn(tuple(w / theta))) * theta / math.pi  # type: ignore[arg-type]
    return w


# --- code: optimise_3d --------------------------------------------------------------------------


def optimise_3d(text: str, iterations: int) -> Array:
    """Read EDGE3 text, run ``iterations`` Gauss-Newton steps from the composed odometry with
    pose 0 fixed; return the positions seen from pose 0 (``(n, 3)``, metres)."""
    graph = se3.parse_edge3(text)
    x, _ = se3.gauss_newton(graph.poses, graph, int(iterations))
    return se3.positions_from_first(x)


@lru_cache(maxsize=8)
def sphere_window(first: int, count: int) -> str:
    """sphere2500's poses ``first … first+count−1`` and every edge among them, renumbered from
    0, as EDGE3 lines in the file's own order and its own digits."""
    lines = []
    for line in sphere_text().splitlines():
        f = line.split()
        i, j = int(f[1]), int(f[2])
        if first <= i < first + count and first <= j < first + count:
            lines.append(" ".join(["EDGE3", str(i - first), str(j - first), *f[3:]]))
    return "\n".join(lines) + "\n"


def graph_inputs() -> Any:
    """Windows of sphere2500 (40–100 poses, with their loop closures) and synthetic graphs of
    2–30 poses with large rotations, 10 or 15 iterations (each converges within them)."""
    from hypothesis import strategies as st

    def window(first: int, count: int) -> dict[str, Any]:
        return {"text": sphere_window(first, count), "iterations": 10}

    def synthetic(seed: int, n: int, loops: int, correlated: bool, it: int) -> dict[str, Any]:
        _, text = se3.simulate(seed, n, loops, correlated=correlated)
        return {"text": text, "iterations": it}

    real = st.builds(window, st.integers(0, 2200), st.integers(40, 100))
    made = st.builds(
        synthetic,
        st.integers(0, 2**32 - 1),
        st.integers(2, 30),
        st.integers(0, 8),
        st.booleans(),
        st.sampled_from([10, 15]),
    )
    return st.one_of(real, made)


def whole_input() -> Any:
    """The whole sphere2500 graph with ten iterations (its only drawn input)."""
    from hypothesis import strategies as st

    return st.just({"text": sphere_text(), "iterations": WHOLE_ITERATIONS})


def _graph(text: str) -> se3.Graph3 | None:
    try:
        graph = se3.parse_edge3(text)
    except Exception:  # not the EDGE3 text the prompt describes
        return None
    return graph if len(graph.poses) >= 2 else None


def graph_valid(text: str, iterations: int) -> bool:
    """The prompt's domain: EDGE3 text with the odometry chain 0…n−1, and an iteration count
    within which Gauss-Newton has converged (or 0); a graph of more than 400 poses only with
    the ten iterations the prompt states."""
    graph = _graph(text)
    if graph is None or not 0 <= iterations <= 30:
        return False
    if len(graph.poses) > 400:
        return iterations == WHOLE_ITERATIONS
    if iterations == 0:
        return True
    x, _ = se3.gauss_newton(graph.poses, graph, int(iterations))
    y, _ = se3.gauss_newton(x, graph, 2)
    change = se3.positions_from_first(x) - se3.positions_from_first(y)
    return bool(np.max(np.abs(change)) < 1e-9)


def _as_information(graph: se3.Graph3) -> se3.Graph3:
    """The 21 numbers mirrored into a symmetric Ω (read as information, g2o style)."""
    s = np.swapaxes(np.linalg.cholesky(graph.omega), -1, -2)  # recovers S (upper, positive)
    omega = np.triu(s) + np.swapaxes(np.triu(s, 1), -1, -2)
    return se3.Graph3(graph.poses, graph.i, graph.j, graph.z, omega)


def mistake_optimise_information(text: str, iterations: int) -> Array:
    graph = _as_information(se3.parse_edge3(text))
    x, _ = se3.gauss_newton(graph.poses, graph, int(iterations))
    return se3.positions_from_first(x)


def _no_jr_inverse(x: Array, graph: se3.Graph3) -> tuple[Array, Array, Array]:
    e, a, b = se3.edge_errors(x, graph)
    jr = se3.right_jacobian(e[:, 3:])  # undo J_r⁻¹: D becomes diag(R_E, I)
    b[:, 3:, 3:] = b[:, 3:, 3:] @ jr
    a[:, 3:, :] = jr @ a[:, 3:, :]
    return e, a, b


def mistake_optimise_no_jr_inverse(text: str, iterations: int) -> Array:
    """``∂Log(R_E)/∂φ`` taken as the identity (``J_r⁻¹`` dropped): Gauss-Newton's fixed point
    is not the minimum."""
    graph = se3.parse_edge3(text)
    x, _ = se3.gauss_newton(graph.poses, graph, int(iterations), model=_no_jr_inverse)
    return se3.positions_from_first(x)


def mistake_optimise_xyz_euler(text: str, iterations: int) -> Array:
    """The angles composed as ``Rx(roll) Ry(pitch) Rz(yaw)``."""
    graph = se3.parse_edge3(text)
    fields = [line.split() for line in text.splitlines() if line.split()[:1] == ["EDGE3"]]
    angles = np.array([[float(v) for v in f[6:9]] for f in fields])
    rx = se3.rpy_matrix(angles[:, 0], 0 * angles[:, 0], 0 * angles[:, 0])
    ry = se3.rpy_matrix(0 * angles[:, 0], angles[:, 1], 0 * angles[:, 0])
    rz = se3.rpy_matrix(0 * angles[:, 0], 0 * angles[:, 0], angles[:, 2])
    z = graph.z.copy()
    z[:, :3, :3] = rx @ ry @ rz
    wrong = se3.Graph3(graph.poses, graph.i, graph.j, z, graph.omega)
    start = np.empty_like(graph.poses)
    start[0] = np.eye(4)
    step = {
        (int(a), int(b)): k
        for k, (a, b) in enumerate(zip(graph.i, graph.j, strict=True))
        if b == a + 1
    }
    for k in range(1, len(start)):
        start[k] = start[k - 1] @ z[step[(k - 1, k)]]
    x, _ = se3.gauss_newton(start, wrong, int(iterations))
    return se3.positions_from_first(x)


def mistake_optimise_not_optimised(text: str, iterations: int) -> Array:
    return se3.positions_from_first(se3.parse_edge3(text).poses)
