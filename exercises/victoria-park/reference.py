"""Reference answers for chapter ``victoria-park``: landmark SLAM on the Victoria Park data set.

The data ship with the course in ``data/victoria_park.txt`` (GTSAM's text version; attribution
in ``data/SOURCE.md``). Conventions and mathematics live in :mod:`slamcourse.slam.victoria`:
a LANDMARK line measures the landmark in the robot's frame, ``e = R(θ)ᵀ (l − t) − z`` with
information ``Σ⁻¹``; ODOMETRY lines are pose-graph edges whose six numbers are a covariance;
poses are numbered by increasing id, landmarks by increasing id; pose 0 is held fixed.
Functions whose name starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import posegraph as pg
from slamcourse.slam import victoria as vp

Matrix = NDArray[np.float64]
DATA = Path(__file__).resolve().parent / "data" / "victoria_park.txt"
STRIDE = 2000  # poses added per batch when the whole park is optimised
# windows of the real park that the optimiser is graded on: (first pose, iterations)
WINDOWS = ((300, 15), (2400, 10))
WINDOW_POSES = 100


@lru_cache(maxsize=1)
def text() -> str:
    return DATA.read_text(encoding="utf-8")


@lru_cache(maxsize=1)
def park() -> vp.LandmarkData:
    return vp.parse_victoria(text())


@lru_cache(maxsize=1)
def batches() -> tuple[Matrix, Matrix, list[vp.Stage]]:
    """The whole park optimised in batches of ``STRIDE`` poses: poses (n×3), landmarks (m×2)
    and the batches (:class:`slamcourse.slam.victoria.Stage`)."""
    return vp.incremental(park(), STRIDE)


def optimum() -> tuple[Matrix, Matrix]:
    x, landmarks, _ = batches()
    return x, landmarks


# --- numeric exercises ------------------------------------------------------------------------


def landmark_count() -> int:
    return park().m


def mistake_count_edges_as_poses() -> int:
    """All ids minus the number of ODOMETRY lines: a chain has one pose more than edges."""
    data = park()
    return data.n + data.m - len(data.odometry)


def degrees_of_freedom() -> int:
    return vp.degrees_of_freedom(park())


def mistake_dof_gauge_ignored() -> int:
    return degrees_of_freedom() - 3


def mistake_dof_landmarks_three() -> int:
    """Landmarks counted with three unknowns each, like poses."""
    return degrees_of_freedom() - park().m


def mistake_dof_poses_only() -> int:
    """Only the poses counted as unknowns: the landmarks' coordinates forgotten."""
    return degrees_of_freedom() + 2 * park().m


def xy_error(**p: float) -> list[float]:
    """``e = R(θ)ᵀ (l − t) − z`` for the parameters ``xr, yr, tr, lx, ly, zx, zy`` (metres)."""
    pose, tree, z = (p["xr"], p["yr"], p["tr"]), (p["lx"], p["ly"]), (p["zx"], p["zy"])
    return vp.landmark_error(pose, tree, z).tolist()  # type: ignore[no-any-return]


def mistake_xy_error_flipped(**p: float) -> list[float]:
    """``z − h`` instead of ``h − z``."""
    return [-v for v in xy_error(**p)]


def mistake_xy_error_rotation(**p: float) -> list[float]:
    """``R(θ) (l − t) − z``: the offset rotated the wrong way."""
    c, s = math.cos(p["tr"]), math.sin(p["tr"])
    dx, dy = p["lx"] - p["xr"], p["ly"] - p["yr"]
    return [c * dx - s * dy - p["zx"], s * dx + c * dy - p["zy"]]


def mistake_xy_error_world(**p: float) -> list[float]:
    """``(l − t) − z``: the robot-frame measurement compared with a world-frame offset."""
    return [p["lx"] - p["xr"] - p["zx"], p["ly"] - p["yr"] - p["zy"]]


def gtsam_sideways(c11: float, r: float) -> float:
    """GTSAM's ``σ_bearing = √(c11/10)`` carried to a tree ``r`` metres away: ``r σ_bearing``."""
    return r * vp.gtsam_sigmas(c11)[0]


def mistake_sideways_at_ten(c11: float, r: float) -> float:
    """``σ_xy`` scaled from 10 m to ``r`` (what "the uncertainty at 10 m" would mean)."""
    return math.sqrt(c11) * r / 10


def mistake_sideways_xy(c11: float, r: float) -> float:
    """The x-y reading: ``√c11`` whatever the range."""
    return math.sqrt(c11)


def mistake_sideways_radians(c11: float, r: float) -> float:
    """``σ_bearing`` itself, not multiplied by the range."""
    return vp.gtsam_sigmas(c11)[0]


def nonzero_blocks() -> int:
    """Non-zero blocks of ``H`` (both triangles): one per variable on the diagonal, two per
    ODOMETRY line and two per distinct pose–landmark pair."""
    data = park()
    pairs = {(int(i), int(k)) for i, k in zip(data.seen_from, data.seen, strict=True)}
    return data.n + data.m + 2 * len(data.odometry) + 2 * len(pairs)


def mistake_blocks_one_triangle() -> int:
    data = park()
    return data.n + data.m + len(data.odometry) + len(data.measured)


def mistake_blocks_no_diagonal() -> int:
    data = park()
    return nonzero_blocks() - data.n - data.m


@lru_cache(maxsize=1)
def group_chi2() -> tuple[float, float, float, float]:
    """At the optimum: χ² of the ODOMETRY lines, of the LANDMARK lines, and the expected value
    of each (its redundancy) were the file's covariances right."""
    x, landmarks = optimum()
    data = park()
    r_odo, r_obs = vp.redundancy(x, landmarks, data)
    return (
        float(vp.odometry_chi2(x, data).sum()),
        float(vp.observation_chi2(x, landmarks, data).sum()),
        r_odo,
        r_obs,
    )


def odometry_factor(chi_odo: float, r_odo: float) -> float:
    """The factor by which every odometry covariance should grow for its χ² to match."""
    return chi_odo / r_odo


def mistake_factor_per_component(chi_odo: float, r_odo: float) -> float:
    """χ² divided by the number of odometry error components (3 per line)."""
    return chi_odo / (3 * len(park().odometry))


def mistake_factor_sigma(chi_odo: float, r_odo: float) -> float:
    """The factor for the standard deviations, not the covariances."""
    return math.sqrt(chi_odo / r_odo)


def mistake_factor_inverted(chi_odo: float, r_odo: float) -> float:
    return r_odo / chi_odo


# --- code: landmark_jacobian ------------------------------------------------------------------


def landmark_jacobian(pose: Sequence[float], landmark: Sequence[float]) -> Matrix:
    """``[∂e/∂(x, y, θ) | ∂e/∂(l_x, l_y)]`` of ``e = R(θ)ᵀ (l − t) − z``, shape (2, 5)."""
    a, b = vp.landmark_jacobians(pose, landmark)
    return np.hstack([a, b])


def mistake_jacobian_heading_sign(pose: Sequence[float], landmark: Sequence[float]) -> Matrix:
    """``∂h/∂θ = (−h_y, h_x)``: the derivative of ``R(θ)ᵀ`` with the wrong sign."""
    out = landmark_jacobian(pose, landmark)
    out[:, 2] *= -1
    return out


def mistake_jacobian_not_transposed(pose: Sequence[float], landmark: Sequence[float]) -> Matrix:
    """``R(θ)`` where ``R(θ)ᵀ`` belongs (both blocks); the heading column of ``R(θ)(l − t)``."""
    c, s = math.cos(float(pose[2])), math.sin(float(pose[2]))
    dx, dy = float(landmark[0]) - float(pose[0]), float(landmark[1]) - float(pose[1])
    r = np.array([[c, -s], [s, c]])
    out = np.zeros((2, 5))
    out[:, :2] = -r
    out[:, 2] = (-s * dx - c * dy, c * dx - s * dy)
    out[:, 3:] = r
    return out


def mistake_jacobian_landmark_sign(pose: Sequence[float], landmark: Sequence[float]) -> Matrix:
    """``∂e/∂l = −R(θ)ᵀ``: the landmark block with the pose block's sign."""
    out = landmark_jacobian(pose, landmark)
    out[:, 3:] *= -1
    return out


def mistake_jacobian_no_heading(pose: Sequence[float], landmark: Sequence[float]) -> Matrix:
    out = landmark_jacobian(pose, landmark)
    out[:, 2] = 0.0
    return out


def _real_pairs() -> list[dict[str, list[float]]]:
    """Pose and landmark of every 40th LANDMARK line of the park, at the initial guess."""
    data = park()
    x, landmarks = vp.initial_guess(data)
    return [
        {
            "pose": [round(float(v), 6) for v in x[data.seen_from[k]]],
            "landmark": [round(float(v), 6) for v in landmarks[data.seen[k]]],
        }
        for k in range(0, len(data.measured), 40)
    ]


def jacobian_inputs() -> Any:
    """Poses and landmarks of real lines of the park, and drawn ones: a pose anywhere in
    [−300, 300] m with any heading and a tree 0–30 m from it."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    def drawn(x: float, y: float, t: float, r: float, a: float) -> dict[str, list[float]]:
        lx = min(max(round(x + r * math.cos(a), 6), -300.0), 300.0)
        ly = min(max(round(y + r * math.sin(a), 6), -300.0), 300.0)
        return {"pose": [x, y, t], "landmark": [lx, ly]}

    made = st.builds(
        drawn,
        real(-300, 300),
        real(-300, 300),
        real(-math.pi, math.pi),
        real(0, 30),
        real(-math.pi, math.pi),
    )
    return st.one_of(st.sampled_from(_real_pairs()), made)


def jacobian_valid(pose: Sequence[float], landmark: Sequence[float]) -> bool:
    """A pose (x, y in [−300, 300] m, θ in [−π, π]) and a landmark in the same square."""
    if len(pose) != 3 or len(landmark) != 2:
        return False
    coords = [float(pose[0]), float(pose[1]), float(landmark[0]), float(landmark[1])]
    return all(abs(v) <= 300 for v in coords) and abs(float(pose[2])) <= math.pi


# --- code: optimise_landmarks -----------------------------------------------------------------


def optimise_landmarks(text: str, iterations: int) -> Matrix:
    """Read, run ``iterations`` Gauss-Newton steps (pose 0 fixed) from dead reckoning and first
    sightings, return the state seen from pose 0 (3n + 2m numbers)."""
    return vp.optimise(text, int(iterations))


@lru_cache(maxsize=8)
def park_window(first: int) -> str:
    """Poses ``first … first+WINDOW_POSES-1`` of the park, their ODOMETRY and LANDMARK lines, ids kept."""
    return vp.window(text(), first, WINDOW_POSES)


def optimise_inputs() -> Any:
    """Two 100-pose windows of the park (10 or 15 steps), then synthetic drives of 2–30 poses
    and 1–8 trees in GTSAM's format, some with ids handed out in a shuffled order."""
    from hypothesis import strategies as st

    real_windows = st.sampled_from(
        [{"text": park_window(first), "iterations": its} for first, its in WINDOWS]
    )

    def synthetic(seed: int, n: int, m: int, shuffle: bool, iterations: int) -> dict[str, Any]:
        return {"text": vp.simulate(seed, n, m, shuffle), "iterations": iterations}

    made = st.builds(
        synthetic,
        st.integers(0, 2**32 - 1),
        st.integers(2, 30),
        st.integers(1, 8),
        st.booleans(),
        st.sampled_from([10, 15]),
    )
    return st.one_of(real_windows, made)


def optimise_valid(text: str, iterations: int) -> bool:
    """``optimise_landmarks``' domain: ODOMETRY lines chaining every pose to the next larger
    id, in file order; LANDMARK lines from poses of the chain; 0–30 steps within which
    Gauss-Newton converges (or 0: the initial guess); no heading seen from pose 0 within 10⁻⁶
    of ±π (where two correct answers may wrap either way)."""
    try:
        data = vp.parse_victoria(text)
    except (ValueError, IndexError):
        return False
    if data.n < 2 or not 0 <= iterations <= 30 or len(data.odometry) != data.n - 1:
        return False
    if not np.array_equal(data.odometry_from, np.arange(data.n - 1)):
        return False
    if not np.array_equal(data.odometry_to, np.arange(1, data.n)):
        return False
    if np.any(np.linalg.eigvalsh(data.odometry_cov) <= 0) or (
        len(data.measured_cov) and np.any(np.linalg.eigvalsh(data.measured_cov) <= 0)
    ):
        return False
    x, landmarks = vp.initial_guess(data)
    x, landmarks, _ = vp.gauss_newton(x, landmarks, data, int(iterations))
    state = vp.relative_state(x, landmarks)
    if not np.all(np.isfinite(state)):
        return False
    headings = state[: 3 * data.n][2::3]
    if np.min(math.pi - np.abs(headings)) < 1e-6:
        return False
    if iterations == 0:
        return True
    y, more, _ = vp.gauss_newton(x, landmarks, data, 3)
    return bool(np.max(np.abs(vp.relative_state(y, more) - state)) < 1e-8)


def _solve(
    text: str,
    iterations: int,
    *,
    odometry_scale: float = 1.0,
    landmark_scale: float = 1.0,
    model: str = "xy",
) -> Matrix:
    data = vp.parse_victoria(text)
    x, landmarks = vp.initial_guess(data)
    data = vp.rescaled(data, odometry_scale, landmark_scale)
    x, landmarks, _ = vp.gauss_newton(x, landmarks, data, int(iterations), model)
    return vp.relative_state(x, landmarks)


def mistake_optimise_covariance_as_information(text: str, iterations: int) -> Matrix:
    """Every line's covariance used as its information matrix (never inverted)."""
    data = vp.parse_victoria(text)
    x, landmarks = vp.initial_guess(data)
    inverted = vp.LandmarkData(
        pose_ids=data.pose_ids,
        landmark_ids=data.landmark_ids,
        odometry_from=data.odometry_from,
        odometry_to=data.odometry_to,
        odometry=data.odometry,
        odometry_cov=np.linalg.inv(data.odometry_cov),
        seen_from=data.seen_from,
        seen=data.seen,
        measured=data.measured,
        measured_cov=np.linalg.inv(data.measured_cov),
        edges=tuple(
            pg.Edge(e.i, e.j, e.z, c) for e, c in zip(data.edges, data.odometry_cov, strict=True)
        ),
    )
    x, landmarks, _ = vp.gauss_newton(x, landmarks, inverted, int(iterations))
    return vp.relative_state(x, landmarks)


def mistake_optimise_gtsam_reading(text: str, iterations: int) -> Matrix:
    """GTSAM's reader: bearing and range with ``σ_b = √(c11/10)``, ``σ_r = √c11``."""
    return _solve(text, iterations, model="gtsam")


def mistake_optimise_not_optimised(text: str, iterations: int) -> Matrix:
    """The initial guess: the steps never reached the result."""
    return vp.optimise(text, 0)
