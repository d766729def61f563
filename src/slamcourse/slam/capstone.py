"""Sizing a 2D LiDAR SLAM system: the figures of chapter 9 (the capstone).

Units: seconds, hertz, metres, radians, bytes, milliseconds, as named in each function.
"""

from __future__ import annotations

import math

from slamcourse.slam import occupancy

DOUBLE_BYTES = 8


def keyframes(minutes: float, rate_hz: float, keyframe_every: int) -> int:
    """Pose variables kept: ``minutes · 60 · rate_hz`` frames, one keyframe every
    ``keyframe_every`` frames."""
    frames = round(minutes * 60 * rate_hz)
    return frames // keyframe_every


def graph_variables(
    minutes: float, rate_hz: float, keyframe_every: int, landmarks_per_keyframe: int
) -> tuple[int, int]:
    """``(poses, landmarks)`` in the factor graph after the run."""
    poses = keyframes(minutes, rate_hz, keyframe_every)
    return poses, poses * landmarks_per_keyframe


def graph_dof(poses: int, landmarks: int, pose_dof: int = 3, landmark_dof: int = 2) -> int:
    """Scalar unknowns of the graph (2D: 3 per pose, 2 per landmark)."""
    return poses * pose_dof + landmarks * landmark_dof


def odometry_step_sigma(
    step: float, distance_error: float, heading_error_deg_per_m: float
) -> tuple[float, float]:
    """``(σ_pos [m], σ_θ [rad])`` of one straight odometry step of ``step`` metres, with a
    distance error that is the fraction ``distance_error`` of the distance and a heading error of
    ``heading_error_deg_per_m`` degrees per metre driven."""
    return distance_error * step, math.radians(heading_error_deg_per_m * step)


def odometry_step_sigma_per_metre(
    step: float, calibration: float, sigma_distance: float, sigma_heading: float
) -> tuple[float, float]:
    """``(σ_pos [m], σ_θ [rad])`` of one straight step of ``step`` metres, for odometry whose
    errors are independent from one stretch of floor to the next, calibrated as the standard
    deviations ``sigma_distance`` (m) and ``sigma_heading`` (rad) over ``calibration`` metres.

    Such errors have a *variance per metre* (``σ²/calibration``): a step of ``s`` metres has
    variance ``s σ²/calibration``, so its standard deviation scales with ``√(s/calibration)``,
    and summing the steps' variances gives the same total for any cut of a drive into steps.
    """
    scale = math.sqrt(step / calibration)
    return sigma_distance * scale, sigma_heading * scale


def random_walk(sigma_step: float, steps: int) -> float:
    """Standard deviation after ``steps`` independent steps of ``sigma_step`` each: ``σ √k``."""
    return sigma_step * math.sqrt(steps)


def lateral_drift(distance: float, heading_error: float) -> float:
    """Sideways offset (m) after driving ``distance`` metres straight with a constant heading
    error of ``heading_error`` radians."""
    return distance * math.sin(heading_error)


def scan_readings(fov_deg: float, resolution_deg: float, hit_fraction: float) -> float:
    """Expected valid range readings per scan: rays ``fov / resolution`` times the fraction that
    hit something within range."""
    return fov_deg / resolution_deg * hit_fraction


def landmarks_per_scan(valid_readings: float, rays_per_landmark: float) -> float:
    """Expected landmarks (corners) per scan, one every ``rays_per_landmark`` valid readings."""
    return valid_readings / rays_per_landmark


def grid_bytes(side: float, resolution: float, bytes_per_cell: int = 1) -> int:
    """Memory of a dense square 2D occupancy grid."""
    return occupancy.grid_cells(side, resolution, 2) * bytes_per_cell


def graph_bytes(
    poses: int,
    landmarks: int,
    blocks_per_variable: int = 3,
    pose_dof: int = 3,
    landmark_dof: int = 2,
) -> int:
    """Memory of the graph's state in doubles: the mean (one number per scalar unknown) and a
    sparse information matrix with ``blocks_per_variable`` stored blocks per variable, taken as
    ``d × d`` for a variable of dimension ``d`` (the sizing rule of thumb of the chapter)."""
    mean = graph_dof(poses, landmarks, pose_dof, landmark_dof)
    blocks = blocks_per_variable * (poses * pose_dof**2 + landmarks * landmark_dof**2)
    return (mean + blocks) * DOUBLE_BYTES


def dense_information_bytes(
    poses: int, landmarks: int, pose_dof: int = 3, landmark_dof: int = 2
) -> int:
    """Memory of the information matrix stored dense: ``n² `` doubles."""
    n = graph_dof(poses, landmarks, pose_dof, landmark_dof)
    return n * n * DOUBLE_BYTES


def frame_budget(rate_hz: float) -> float:
    """Time available per frame (ms) at ``rate_hz``."""
    return 1000.0 / rate_hz


def frame_headroom(rate_hz: float, stage_ms: list[float]) -> tuple[float, float]:
    """``(total, headroom)`` in ms: the summed stage times and what is left of the frame budget
    (negative when the pipeline does not fit)."""
    total = math.fsum(stage_ms)
    return total, frame_budget(rate_hz) - total
