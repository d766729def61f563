"""Reference code for chapter ``vision``: two-view geometry and RANSAC.

Image points are in normalised homogeneous coordinates ``x = [u, v, 1]`` (the pixel coordinates
with the camera intrinsics removed). With the second camera related to the first by the
rotation ``R`` and translation ``t``, the essential matrix is ``E = [t]× R`` where

    [t]× = [[0, −t_z, t_y], [t_z, 0, −t_x], [−t_y, t_x, 0]]

is the matrix with ``[t]× v = t × v``. A correspondence ``x ↔ x′`` of the same 3D point
satisfies the epipolar constraint ``x′ᵀ E x = 0``; with noise, ``x′ᵀ E x`` is the residual.

RANSAC needs ``N = ⌈log(1 − p) / log(1 − wˢ)⌉`` random minimal samples of size ``s`` to draw at
least one sample made only of inliers with probability ``p`` when a fraction ``w`` of the
data are inliers.

Every exercise function takes the exercise's parameters (or a code exercise's arguments) as
keyword arguments. Functions whose name starts with ``mistake_`` are wrong implementations or
wrong answers of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

Vector = Sequence[float]
Matrix = Sequence[Sequence[float]]


# --- RANSAC iteration count -----------------------------------------------------------------


def ransac_ratio(inlier_ratio: float, sample_size: int, confidence: float) -> float:
    """``log(1 − p) / log(1 − wˢ)`` before rounding up (a real number of samples)."""
    return math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size)


def ransac_iterations(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """Number of RANSAC samples ``⌈log(1 − p) / log(1 − wˢ)⌉``."""
    return math.ceil(ransac_ratio(inlier_ratio, sample_size, confidence))


def mistake_ransac_rounded(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """Rounded to the nearest integer instead of up."""
    return round(ransac_ratio(inlier_ratio, sample_size, confidence))


def mistake_ransac_floored(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """Rounded down (``floor`` or ``int``) instead of up."""
    return math.floor(ransac_ratio(inlier_ratio, sample_size, confidence))


def mistake_ransac_outlier_ratio(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """``(1 − w)ˢ`` (the chance of an all-outlier sample) in place of ``wˢ``."""
    return ransac_iterations(1 - inlier_ratio, sample_size, confidence)


def mistake_ransac_no_exponent(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """``w`` in place of ``wˢ``: as if a sample were a single point."""
    return ransac_iterations(inlier_ratio, 1, confidence)


# --- the epipolar residual ------------------------------------------------------------------


def epipolar_residual(E: Matrix, x: Vector, x2: Vector) -> float:
    """``x′ᵀ E x`` for the essential matrix ``E`` (3 × 3), ``x`` in image 1, ``x2`` in image 2."""
    E_x = np.asarray(E, dtype=float) @ np.asarray(x, dtype=float)
    return float(np.asarray(x2, dtype=float) @ E_x)


def epipolar_inputs() -> Any:
    """Hypothesis strategy for ``epipolar_residual``: ``E = [t]× R`` of a relative pose (``t`` in
    [−3, 3]³ m, a proper rotation ``R``), as a list of rows, and two normalised image points
    ``[u, v, 1]`` with ``u, v`` in [−1.5, 1.5] (a field of view up to 112°). Half of the draws
    make ``x2`` the true match of ``x`` (a point 0.5–50 m in front of camera 1 that camera 2
    also sees within the same range of ``u, v``): there the residual is zero up to rounding.
    A quarter of the draws use an arbitrary ``E`` with entries in [−2, 2] instead (like the
    lesson's example matrix, which is not the essential matrix of any pose)."""
    from hypothesis import strategies as st

    coord = st.floats(-1.5, 1.5, allow_nan=False, allow_infinity=False)
    point = st.builds(lambda u, v: [u, v, 1.0], coord, coord)
    entry = st.floats(-2.0, 2.0, allow_nan=False, allow_infinity=False)
    any_matrix = st.lists(st.lists(entry, min_size=3, max_size=3), min_size=3, max_size=3)

    @st.composite
    def inputs(draw: Any) -> dict[str, Any]:
        pose = draw(essential_inputs())
        E = essential_matrix(pose["t"], pose["R"])
        x = draw(point)
        x2 = draw(point)
        if draw(st.integers(0, 3)) == 0:
            return {"E": draw(any_matrix), "x": x, "x2": x2}
        if draw(st.booleans()):
            depth = draw(st.floats(0.5, 50.0, allow_nan=False, allow_infinity=False))
            X2 = np.asarray(pose["R"]) @ (depth * np.asarray(x)) + np.asarray(pose["t"])
            if X2[2] > 0.1 and max(abs(X2[0]), abs(X2[1])) <= 1.5 * X2[2]:
                x2 = [float(X2[0] / X2[2]), float(X2[1] / X2[2]), 1.0]
        return {"E": E.tolist(), "x": x, "x2": x2}

    return inputs()


def mistake_epipolar_transposed(E: Matrix, x: Vector, x2: Vector) -> float:
    """``xᵀ E x′``: the two points swapped (the constraint of Eᵀ)."""
    return epipolar_residual(E, x2, x)


def epipolar_value(u1: float, v1: float, u2: float, v2: float) -> float:
    """``x′ᵀ E x`` for the lesson's E, ``x = [u1, v1, 1]`` and ``x′ = [u2, v2, 1]``."""
    return epipolar_residual(LESSON_E, [u1, v1, 1.0], [u2, v2, 1.0])


def mistake_epipolar_value_transposed(u1: float, v1: float, u2: float, v2: float) -> float:
    """``xᵀ E x′`` for the lesson's E."""
    return epipolar_residual(LESSON_E, [u2, v2, 1.0], [u1, v1, 1.0])


LESSON_E = [[0.0, -1.0, 0.0], [1.0, 0.0, -0.5], [0.0, 0.3, 0.0]]


# --- the essential matrix from a relative pose ----------------------------------------------


def skew(t: Vector) -> NDArray[np.float64]:
    """``[t]×``: the 3 × 3 matrix with ``skew(t) @ v == np.cross(t, v)``."""
    tx, ty, tz = (float(c) for c in t)
    return np.array([[0.0, -tz, ty], [tz, 0.0, -tx], [-ty, tx, 0.0]])


def essential_matrix(t: Vector, R: Matrix) -> NDArray[np.float64]:
    """``E = [t]× R`` (3 × 3) for translation ``t`` (3,) and rotation ``R`` (3 × 3)."""
    return skew(t) @ np.asarray(R, dtype=float)


def rotation_from_quaternion(q: Vector) -> NDArray[np.float64]:
    """The rotation matrix of the (not necessarily unit) quaternion ``q = (w, x, y, z)``."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def essential_inputs() -> Any:
    """Hypothesis strategy for ``essential_matrix``: ``t`` in [−3, 3]³ and a proper rotation ``R``
    (orthonormal, det +1; from a random quaternion of norm ≥ 0.5), both as plain lists."""
    from hypothesis import strategies as st

    coord = st.floats(-3.0, 3.0, allow_nan=False, allow_infinity=False)
    quat = st.lists(st.floats(-1.0, 1.0, allow_nan=False, allow_infinity=False),
                    min_size=4, max_size=4).filter(lambda q: math.fsum(c * c for c in q) >= 0.25)
    return st.fixed_dictionaries({
        "t": st.lists(coord, min_size=3, max_size=3),
        "R": quat.map(lambda q: rotation_from_quaternion(q).tolist()),
    })


def mistake_essential_wrong_order(t: Vector, R: Matrix) -> NDArray[np.float64]:
    """``R [t]×``: the factors multiplied in the wrong order."""
    return np.asarray(R, dtype=float) @ skew(t)


def mistake_essential_skew_sign(t: Vector, R: Matrix) -> NDArray[np.float64]:
    """``[t]×ᵀ R = −[t]× R``: the skew matrix built with the opposite sign convention."""
    return -essential_matrix(t, R)


def mistake_essential_cross_rows(t: Vector, R: Matrix) -> NDArray[np.float64]:
    """``t × (row k of R)`` as row k: the rows of R crossed instead of its columns."""
    return np.cross(np.asarray(t, dtype=float), np.asarray(R, dtype=float))


# --- RANSAC: scoring candidate lines --------------------------------------------------------


def point_line_distance(a: Vector, b: Vector, q: Vector) -> float:
    """Perpendicular distance from ``q`` to the line through ``a`` and ``b`` (a ≠ b)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    return abs(dx * (q[1] - a[1]) - dy * (q[0] - a[0])) / math.hypot(dx, dy)


def inlier_counts(points: Sequence[Vector], samples: Sequence[Sequence[int]],
                  threshold: float) -> list[int]:
    """For each sample ``(a, b)``: how many of ``points`` lie closer than ``threshold`` to the
    line through ``points[a]`` and ``points[b]``."""
    return [sum(point_line_distance(points[a], points[b], q) < threshold for q in points)
            for a, b in samples]


def best_line(points: Sequence[Vector], samples: Sequence[Sequence[int]], threshold: float) -> int:
    """Index (into ``samples``) of the candidate line with the most inliers among all points;
    the first such index on ties."""
    counts = inlier_counts(points, samples, threshold)
    return counts.index(max(counts))


def mistake_best_line_sample_only(points: Sequence[Vector], samples: Sequence[Sequence[int]],
                                  threshold: float) -> int:
    """The buggy loop: inliers counted among the sample's own two points, so every candidate
    scores 2 and the first one wins."""
    counts = [sum(point_line_distance(points[a], points[b], points[k]) < threshold
                  for k in (a, b)) for a, b in samples]
    return counts.index(max(counts))


def mistake_best_line_vertical_distance(points: Sequence[Vector],
                                        samples: Sequence[Sequence[int]],
                                        threshold: float) -> int:
    """Inliers judged by the vertical gap ``|y − (m x + c)|`` instead of the perpendicular
    distance (a steep line then has almost no inliers)."""
    counts = []
    for a, b in samples:
        (xa, ya), (xb, yb) = points[a], points[b]
        if xb == xa:  # no slope: only points exactly on the vertical line have a finite gap
            counts.append(sum(q[0] == xa for q in points))
            continue
        m = (yb - ya) / (xb - xa)
        counts.append(sum(abs(q[1] - (ya + m * (q[0] - xa))) < threshold for q in points))
    return counts.index(max(counts))


def mistake_best_line_returns_count(points: Sequence[Vector], samples: Sequence[Sequence[int]],
                                    threshold: float) -> int:
    """The best inlier count returned instead of the index of the best sample."""
    return max(inlier_counts(points, samples, threshold))


def ransac_line_inputs() -> Any:
    """Hypothesis strategy for ``best_line``.

    ``threshold`` is in [0.05, 1] m. Points (lists ``[x, y]``, metres, within ±30 m) are 3–12
    points near a random line (perpendicular noise up to 0.8 × threshold) and 2–10 scattered
    points, shuffled. ``samples`` holds 1–8 pairs of distinct point indices whose points are at
    least 0.5 m apart; a pair may repeat or appear reversed (RANSAC draws with replacement), so
    ties happen. Draws are kept only when no point lies within 1e-6 m of the threshold, so the
    answer never hinges on rounding (exact boundaries are tested by the explicit examples).
    """
    from hypothesis import strategies as st

    num = st.floats(-30.0, 30.0, allow_nan=False, allow_infinity=False)

    @st.composite
    def data(draw: Any) -> dict[str, Any]:
        threshold = draw(st.floats(0.05, 1.0, allow_nan=False))
        angle = draw(st.floats(0.0, math.pi, allow_nan=False))
        offset = draw(st.floats(-10.0, 10.0, allow_nan=False))
        d = (math.cos(angle), math.sin(angle))
        nrm = (-d[1], d[0])
        noise = st.floats(-0.8 * threshold, 0.8 * threshold, allow_nan=False)
        points = []
        for _ in range(draw(st.integers(3, 12))):
            s = draw(st.floats(-20.0, 20.0, allow_nan=False))
            e = offset + draw(noise)
            points.append([e * nrm[0] + s * d[0], e * nrm[1] + s * d[1]])
        for _ in range(draw(st.integers(2, 10))):
            points.append([draw(num), draw(num)])
        points = draw(st.permutations(points))
        n = len(points)
        pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(
            lambda p: math.dist(points[p[0]], points[p[1]]) >= 0.5)
        samples = [list(p) for p in draw(st.lists(pair, min_size=1, max_size=8))]
        if len(samples) > 1 and draw(st.booleans()):  # a repeated draw, possibly reversed
            a, b = draw(st.sampled_from(samples))
            again = [b, a] if draw(st.booleans()) else [a, b]
            samples.insert(draw(st.integers(0, len(samples))), again)
        return {"points": points, "samples": samples, "threshold": threshold}

    def clean(kw: dict[str, Any]) -> bool:
        pts, thr = kw["points"], kw["threshold"]
        return all(abs(point_line_distance(pts[a], pts[b], q) - thr) >= 1e-6
                   for a, b in kw["samples"] for q in pts)

    return data().filter(clean)


# --- numeric exercises ----------------------------------------------------------------------


def five_point_minimum() -> int:
    """Correspondences needed for E: 6 parameters (3 rotation, 3 translation) minus 1 for the
    unknown scale leave 5 degrees of freedom, and each correspondence gives one equation."""
    rotation, translation, scale = 3, 3, 1
    return rotation + translation - scale


def mistake_five_point_eight() -> int:
    """The 8 correspondences of the linear 8-point algorithm."""
    return 8


def mistake_five_point_six() -> int:
    """The 6 pose parameters, forgetting that the scale cannot be recovered."""
    return 6


def scaled_translation(scale: float, dx: float, dy: float, dz: float,
                       baseline: float) -> list[float]:
    """The translation ``scale · t̂`` (metres) from a unit direction and a known scale."""
    return [scale * dx, scale * dy, scale * dz]


def mistake_translation_baseline(scale: float, dx: float, dy: float, dz: float,
                                 baseline: float) -> list[float]:
    """The stereo baseline used as the scale."""
    return [baseline * dx, baseline * dy, baseline * dz]


# --- the degrees of freedom of E and F, and the singular-value test ------------------------
# (these call the course library ``slamcourse.slam.vision``)

from slamcourse.slam import vision as _vision  # noqa: E402


def essential_dof() -> int:
    """Degrees of freedom of E: 3 (rotation) + 3 (translation) − 1 (scale)."""
    return _vision.ESSENTIAL_DOF


def mistake_dof_scale_kept() -> int:
    """The 6 pose parameters, the invisible scale not removed."""
    return 6


def mistake_dof_entries() -> int:
    """The 9 entries of a 3 × 3 matrix."""
    return 9


def mistake_dof_entries_up_to_scale() -> int:
    """9 entries minus the scale: what the linear 8-point algorithm assumes."""
    return 8


def mistake_dof_fundamental() -> int:
    """The 7 degrees of freedom of the fundamental matrix F."""
    return _vision.FUNDAMENTAL_DOF


def fundamental_dof() -> int:
    """Degrees of freedom of F: 9 entries − 1 (scale) − 1 (det F = 0)."""
    return _vision.FUNDAMENTAL_DOF


def mistake_fdof_no_rank() -> int:
    """9 − 1: the rank-2 constraint det F = 0 forgotten."""
    return 8


def mistake_fdof_essential() -> int:
    """The 5 degrees of freedom of E (F has no rotation-and-translation structure)."""
    return _vision.ESSENTIAL_DOF


def lesson_matrix(a: float, b: float) -> list[list[float]]:
    """The 3 × 3 matrix ``[[0, −1, 0], [1, 0, −a], [0, b, 0]]`` (the lesson's has a = 0.5,
    b = 0.3)."""
    return [[0.0, -1.0, 0.0], [1.0, 0.0, -a], [0.0, b, 0.0]]


def matrix_singular_values(a: float, b: float) -> list[float]:
    """Singular values (largest first) of :func:`lesson_matrix`."""
    return [float(s) for s in _vision.singular_values(lesson_matrix(a, b))]


def mistake_singular_squared(a: float, b: float) -> list[float]:
    """The eigenvalues of ``MᵀM`` (the squared singular values), square root not taken."""
    return [float(s) ** 2 for s in _vision.singular_values(lesson_matrix(a, b))]


def pose_essential(tx: float, ty: float, tz: float, angle: float) -> list[list[float]]:
    """``E = [t]× R_z(angle)`` for the exercise's pose."""
    return _vision.essential_from_pose([tx, ty, tz], _vision.rotation_z(angle)).tolist()


def essential_singular_values(tx: float, ty: float, tz: float, angle: float,
                              **_derived: float) -> list[float]:
    """Singular values of ``[t]× R``: ``(|t|, |t|, 0)``."""
    return [float(s) for s in _vision.singular_values(pose_essential(tx, ty, tz, angle))]


def mistake_essential_sv_squared(tx: float, ty: float, tz: float, angle: float,
                                 **_derived: float) -> list[float]:
    """``(|t|², |t|², 0)``: the eigenvalues of ``EᵀE``, square root not taken."""
    return [float(s) ** 2 for s in essential_singular_values(tx, ty, tz, angle)]


def mistake_essential_sv_translation(tx: float, ty: float, tz: float,
                                     angle: float,
                                     **_derived: float) -> list[float]:
    """The absolute translation components, largest first, taken for the singular values."""
    return sorted((abs(tx), abs(ty), abs(tz)), reverse=True)


# --- from E to F ----------------------------------------------------------------------------


def _k(f: float, cx: float, cy: float) -> NDArray[np.float64]:
    return _vision.intrinsics(f, cx, cy)


def fundamental_of_translation(tx: float, ty: float, tz: float, f: float, cx: float,
                               cy: float) -> list[list[float]]:
    """``F = K⁻ᵀ E K⁻¹`` with ``E = [t]×`` (no rotation) and both cameras' ``K`` alike."""
    E = _vision.skew([tx, ty, tz])
    F = _vision.fundamental_from_essential(E, _k(f, cx, cy))
    F[np.abs(F) < 1e-12 * np.abs(F).max()] = 0.0  # round-off of entries that are exactly 0
    return F.tolist()


def mistake_fundamental_direction(tx: float, ty: float, tz: float, f: float, cx: float,
                                  cy: float) -> list[list[float]]:
    """``Kᵀ E K``: the formula that goes from F back to E, applied the wrong way."""
    K = _k(f, cx, cy)
    return (K.T @ _vision.skew([tx, ty, tz]) @ K).tolist()


def mistake_fundamental_no_transpose(tx: float, ty: float, tz: float, f: float, cx: float,
                                     cy: float) -> list[list[float]]:
    """``K⁻¹ E K⁻¹``: the transpose on the left factor forgotten."""
    Ki = np.linalg.inv(_k(f, cx, cy))
    return (Ki @ _vision.skew([tx, ty, tz]) @ Ki).tolist()


def mistake_fundamental_sides_swapped(tx: float, ty: float, tz: float, f: float, cx: float,
                                      cy: float) -> list[list[float]]:
    """``K⁻¹ E K⁻ᵀ``: the transposed inverse put on the wrong side."""
    Ki = np.linalg.inv(_k(f, cx, cy))
    return (Ki @ _vision.skew([tx, ty, tz]) @ Ki.T).tolist()


# --- RANSAC: better matches, bigger samples, the threshold ----------------------------------


def mistake_ransac_outlier_as_inlier(inlier_ratio: float, sample_size: int,
                                     confidence: float) -> int:
    """The outlier fraction ``1 − w`` used as if it were the inlier ratio."""
    return _vision.ransac_iterations(1 - inlier_ratio, sample_size, confidence)


def mistake_ransac_five_point(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """The count for a 5-point sample, whatever the sample size asked."""
    return _vision.ransac_iterations(inlier_ratio, 5, confidence)


def sampson_threshold(sigma: float, confidence: float) -> float:
    """``τ² = σ² χ²₁(p)`` (px²): threshold on the squared Sampson distance."""
    return _vision.sampson_threshold(sigma, confidence)


def mistake_threshold_unit_sigma(sigma: float, confidence: float) -> float:
    """``χ²₁(p)`` alone: the noise level left out."""
    return _vision.chi2_quantile(confidence, 1)


def mistake_threshold_sigma_not_squared(sigma: float, confidence: float) -> float:
    """``σ χ²₁(p)``: a squared distance scaled by σ instead of σ²."""
    return sigma * _vision.chi2_quantile(confidence, 1)


def mistake_threshold_two_dof(sigma: float, confidence: float) -> float:
    """``σ² χ²₂(p)``: two degrees of freedom, as for a 2D point error."""
    return sigma**2 * _vision.chi2_quantile(confidence, 2)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def epipolar_valid(E: Matrix, x: Vector, x2: Vector) -> bool:
    """``epipolar_residual``'s domain: a 3×3 ``E`` with entries within ±(3√2) (an essential
    matrix of a translation up to 3 m per axis, or any matrix with entries in [−2, 2]), and two
    normalised points ``[u, v, 1]`` with ``u, v`` in [−1.5, 1.5]."""
    e = np.asarray(E, dtype=float)
    if e.shape != (3, 3) or not np.all(np.abs(e) <= 3 * math.sqrt(2) + 1e-9):
        return False
    for p in (x, x2):
        if len(p) != 3 or p[2] != 1 or abs(p[0]) > 1.5 or abs(p[1]) > 1.5:
            return False
    return True


def essential_valid(t: Vector, R: Matrix) -> bool:
    """``essential_matrix``'s domain: ``t`` within [−3, 3] per axis and a proper rotation
    (``R Rᵀ = I``, ``det R = +1``)."""
    r = np.asarray(R, dtype=float)
    if len(t) != 3 or any(abs(c) > 3 for c in t) or r.shape != (3, 3):
        return False
    return bool(np.allclose(r @ r.T, np.eye(3), atol=1e-9) and np.linalg.det(r) > 0)


def ransac_line_valid(points: Sequence[Vector], samples: Sequence[Sequence[int]],
                      threshold: float) -> bool:
    """``best_line``'s domain: up to 22 points within ±30 m, a threshold in [0.05, 1] m, 1–9
    candidate pairs of point indices whose points are at least 0.5 m apart, and no point within
    1e-6 m of the threshold of a candidate's line (where rounding would decide)."""
    if not 1 <= len(points) <= 22 or not 1 <= len(samples) <= 9 or not 0.05 <= threshold <= 1:
        return False
    if any(len(p) != 2 or abs(p[0]) > 30 or abs(p[1]) > 30 for p in points):
        return False
    for s in samples:
        if len(s) != 2 or isinstance(s[0], float) or isinstance(s[1], float):
            return False
        a, b = s
        if not (0 <= a < len(points) and 0 <= b < len(points)):
            return False
        if math.dist(points[a], points[b]) < 0.5:
            return False
    return all(abs(point_line_distance(points[a], points[b], q) - threshold) >= 1e-6
               for a, b in samples for q in points)


def ransac_iterations_valid(inlier_ratio: float, sample_size: int, confidence: float) -> bool:
    """``ransac_iterations``'s domain: ``w`` in [0.1, 0.99], ``s`` in 1–8, ``p`` in
    [0.5, 0.9999], a clean sample not rarer than 10⁻⁴, and an exact count not within rounding
    noise of a whole number, where the formula chosen (log, log1p, a loop) could decide the
    ceiling (exact whole-number ratios are the explicit examples' business)."""
    if not (0.1 <= inlier_ratio <= 0.99 and 1 <= sample_size <= 8 and 0.5 <= confidence <= 0.9999):
        return False
    if inlier_ratio**sample_size < 1e-4:
        return False
    ratio = ransac_ratio(inlier_ratio, sample_size, confidence)
    margin = 1e-7 + 1e-9 * ratio
    return ratio - math.floor(ratio) > margin and math.ceil(ratio) - ratio > margin


# --- Hartley normalisation (issue 16) ---------------------------------------------------------


def _hartley_points(
    x1: float, y1: float, x2: float, y2: float, x3: float, y3: float, x4: float, y4: float
) -> NDArray[np.float64]:
    return np.array([[x1, y1], [x2, y2], [x3, y3], [x4, y4]], dtype=float)


def _similarity(scale: float, cx: float, cy: float) -> list[list[float]]:
    """``T = [[s, 0, −s·cx], [0, s, −s·cy], [0, 0, 1]]``: translate by −c, then scale by s."""
    return [[scale, 0.0, -scale * cx], [0.0, scale, -scale * cy], [0.0, 0.0, 1.0]]


def hartley_matrix(
    x1: float,
    y1: float,
    x2: float,
    y2: float,
    x3: float,
    y3: float,
    x4: float,
    y4: float,
    **_derived: float,
) -> list[list[float]]:
    """Hartley's 3×3 normalising transform of four pixel points: the centroid moves to the
    origin and the mean distance from it becomes √2."""
    pts = _hartley_points(x1, y1, x2, y2, x3, y3, x4, y4)
    c = pts.mean(axis=0)
    mean_distance = float(np.mean(np.hypot(*(pts - c).T)))
    return _similarity(math.sqrt(2) / mean_distance, float(c[0]), float(c[1]))


def mistake_hartley_unit_distance(
    x1: float,
    y1: float,
    x2: float,
    y2: float,
    x3: float,
    y3: float,
    x4: float,
    y4: float,
    **_derived: float,
) -> list[list[float]]:
    """Mean distance scaled to 1 instead of √2."""
    pts = _hartley_points(x1, y1, x2, y2, x3, y3, x4, y4)
    c = pts.mean(axis=0)
    return _similarity(1.0 / float(np.mean(np.hypot(*(pts - c).T))), float(c[0]), float(c[1]))


def mistake_hartley_rms(
    x1: float,
    y1: float,
    x2: float,
    y2: float,
    x3: float,
    y3: float,
    x4: float,
    y4: float,
    **_derived: float,
) -> list[list[float]]:
    """The root-mean-square distance made √2 instead of the mean distance."""
    pts = _hartley_points(x1, y1, x2, y2, x3, y3, x4, y4)
    c = pts.mean(axis=0)
    rms = math.sqrt(float(np.mean(np.sum((pts - c) ** 2, axis=1))))
    return _similarity(math.sqrt(2) / rms, float(c[0]), float(c[1]))


def mistake_hartley_translation_unscaled(
    x1: float,
    y1: float,
    x2: float,
    y2: float,
    x3: float,
    y3: float,
    x4: float,
    y4: float,
    **_derived: float,
) -> list[list[float]]:
    """The last column −c instead of −s·c: the translation written as if it came after the
    scaling."""
    t = hartley_matrix(x1, y1, x2, y2, x3, y3, x4, y4)
    pts = _hartley_points(x1, y1, x2, y2, x3, y3, x4, y4)
    c = pts.mean(axis=0)
    return [[t[0][0], 0.0, -float(c[0])], [0.0, t[1][1], -float(c[1])], [0.0, 0.0, 1.0]]


def mistake_hartley_plus_centroid(
    x1: float,
    y1: float,
    x2: float,
    y2: float,
    x3: float,
    y3: float,
    x4: float,
    y4: float,
    **_derived: float,
) -> list[list[float]]:
    """The centroid added instead of subtracted."""
    t = hartley_matrix(x1, y1, x2, y2, x3, y3, x4, y4)
    return [[t[0][0], 0.0, -t[0][2]], [0.0, t[1][1], -t[1][2]], [0.0, 0.0, 1.0]]


def hartley_rms_gap(
    x1: float,
    y1: float,
    x2: float,
    y2: float,
    x3: float,
    y3: float,
    x4: float,
    y4: float,
    **_derived: float,
) -> float:
    """RMS over mean distance from the centroid, minus 1 (0 when all distances are equal)."""
    pts = _hartley_points(x1, y1, x2, y2, x3, y3, x4, y4)
    d = np.hypot(*(pts - pts.mean(axis=0)).T)
    return float(math.sqrt(float(np.mean(d**2))) / float(np.mean(d)) - 1.0)


# --- code: decompose_essential (issue 16) -----------------------------------------------------

_W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def essential_candidates(E: Matrix) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """The four ``(R, t)`` of ``E = U diag(σ, σ, 0) Vᵀ``: ``R ∈ {U W Vᵀ, U Wᵀ Vᵀ}``,
    ``t = ±u₃`` (unit length), with ``U`` and ``V`` turned into rotations first."""
    u, _, vt = np.linalg.svd(np.asarray(E, dtype=float))
    if np.linalg.det(u) < 0:
        u = -u
    if np.linalg.det(vt) < 0:
        vt = -vt
    out = []
    for r in (u @ _W @ vt, u @ _W.T @ vt):
        for t in (u[:, 2], -u[:, 2]):
            out.append((r, t))
    return out


def two_view_depths(R: Matrix, t: Vector, x1: Vector, x2: Vector) -> tuple[float, float]:
    """Depths ``(z₁, z₂)`` with ``z₂ x₂ = z₁ R x₁ + t`` (least squares; exact without noise)."""
    a = np.column_stack(
        [-(np.asarray(R, dtype=float) @ np.asarray(x1, dtype=float)), np.asarray(x2, dtype=float)]
    )
    z, *_ = np.linalg.lstsq(a, np.asarray(t, dtype=float), rcond=None)
    return float(z[0]), float(z[1])


def decompose_essential(E: Matrix, x1: Vector, x2: Vector) -> NDArray[np.float64]:
    """``[R | t]`` (3 × 4, ``‖t‖ = 1``) with ``X₂ = R X₁ + t``: the one of the four candidates
    that puts the point seen at ``x1`` ↔ ``x2`` in front of both cameras."""
    for r, t in essential_candidates(E):
        z1, z2 = two_view_depths(r, t, x1, x2)
        if z1 > 0 and z2 > 0:
            return np.column_stack([r, t])
    raise ValueError("no candidate puts the point in front of both cameras")


def _rotation_axis_angle(axis: NDArray[np.float64], angle: float) -> NDArray[np.float64]:
    k = axis / np.linalg.norm(axis)
    kx = skew(k)
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def decompose_inputs() -> Any:
    """A relative pose (rotation of up to 0.6 rad about any axis, a translation in any
    direction), ``E = s·[t]×R`` with a scale ``s`` of either sign (0.2 to 5 in size), and one
    noise-free correspondence of a point 2–20 m in front of both cameras."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        axis = np.array([draw(real(-1, 1)) for _ in range(3)])
        if np.linalg.norm(axis) < 0.1:
            axis = np.array([0.0, 1.0, 0.0])
        r = _rotation_axis_angle(axis, draw(real(0.0, 0.6)))
        t = np.array([draw(real(-1, 1)) for _ in range(3)])
        if np.linalg.norm(t) < 0.1:
            t = np.array([1.0, 0.0, 0.0])
        t = t / np.linalg.norm(t) * draw(real(0.2, 2.0))
        s = draw(real(0.2, 5.0)) * draw(st.sampled_from([1.0, -1.0]))
        depth = draw(real(2.0, 20.0))
        p1 = np.array([draw(real(-0.5, 0.5)) * depth, draw(real(-0.4, 0.4)) * depth, depth])
        p2 = r @ p1 + t
        e = s * skew(t) @ r
        return {"E": e.tolist(), "x1": (p1 / p1[2]).tolist(), "x2": (p2 / p2[2]).tolist()}

    return draw()


def decompose_valid(E: Matrix, x1: Vector, x2: Vector) -> bool:
    """``decompose_essential``'s domain: ``E`` an essential matrix (singular values σ, σ, 0 to
    10⁻⁹ relative, 0.05 ≤ σ ≤ 20), ``x1``, ``x2`` normalised points (third entry 1, others within
    ±2) that satisfy ``x2ᵀ E x1 = 0`` to 10⁻⁹, and exactly one candidate with both depths
    positive, each depth at least 0.5, the two rays at least 0.01 rad apart, and every other candidate 0.01 or more behind a camera."""
    try:
        e = np.asarray(E, dtype=float)
        a, b = np.asarray(x1, dtype=float), np.asarray(x2, dtype=float)
    except (TypeError, ValueError):
        return False
    if e.shape != (3, 3) or a.shape != (3,) or b.shape != (3,) or not np.all(np.isfinite(e)):
        return False
    if a[2] != 1 or b[2] != 1 or np.any(np.abs(a[:2]) > 2) or np.any(np.abs(b[:2]) > 2):
        return False
    s = np.linalg.svd(e, compute_uv=False)
    if not (0.05 <= s[0] <= 20 and s[0] - s[1] <= 1e-9 * s[0] and s[2] <= 1e-9 * s[0]):
        return False
    if abs(float(b @ e @ a)) > 1e-9 * s[0]:
        return False
    ahead = []
    for r, t in essential_candidates(e):
        z1, z2 = two_view_depths(r, t, a, b)
        if z1 > 0 and z2 > 0:
            ray = r @ a
            parallax = np.linalg.norm(np.cross(b, ray)) / (np.linalg.norm(b) * np.linalg.norm(ray))
            ahead.append(min(z1, z2) if parallax > 0.01 else 0.0)
        elif min(z1, z2) > -0.01:
            return False
    return len(ahead) == 1 and ahead[0] >= 0.5
