"""Reference code for chapter ``capstone``: sizing a 2D LiDAR SLAM system.

The figures come from the course library :mod:`slamcourse.slam.capstone`; the functions here
adapt it to the exercises' parameters. Units: minutes, hertz, metres, radians, bytes,
milliseconds, as the names say.

Every exercise function takes the exercise's parameters as keyword arguments. Functions whose
name starts with ``mistake_`` are wrong answers of a named misconception.
"""

from __future__ import annotations

import math

from slamcourse.slam import capstone as cap

# --- the factor graph after the run ---------------------------------------------------------


def graph_variables(minutes: float, rate_hz: float, keyframe_every: int,
                    landmarks_per_keyframe: int) -> int:
    """Poses kept as keyframes plus the landmarks they discovered."""
    poses, landmarks = cap.graph_variables(minutes, rate_hz, keyframe_every,
                                           landmarks_per_keyframe)
    return poses + landmarks


def mistake_variables_every_frame(minutes: float, rate_hz: float, keyframe_every: int,
                                  landmarks_per_keyframe: int) -> int:
    """Every frame kept as a pose (no keyframing)."""
    return graph_variables(minutes, rate_hz, 1, landmarks_per_keyframe)


def mistake_variables_poses_only(minutes: float, rate_hz: float, keyframe_every: int,
                                 landmarks_per_keyframe: int) -> int:
    """Only the poses counted; the landmarks are variables too."""
    return cap.keyframes(minutes, rate_hz, keyframe_every)


def mistake_variables_dof(minutes: float, rate_hz: float, keyframe_every: int,
                          landmarks_per_keyframe: int) -> int:
    """The scalar unknowns (3 per pose, 2 per landmark) instead of the variables."""
    return cap.graph_dof(*cap.graph_variables(minutes, rate_hz, keyframe_every,
                                              landmarks_per_keyframe))


# --- odometry uncertainty -------------------------------------------------------------------


def odometry_step(step: float, calibration: float, sigma_dist_cm: float,
                  sigma_heading_deg: float) -> list[float]:
    """``[σ_pos (m), σ_θ (rad)]`` of one straight step, from variances per metre."""
    return list(cap.odometry_step_sigma_per_metre(step, calibration, sigma_dist_cm / 100,
                                                  math.radians(sigma_heading_deg)))


def mistake_step_linear(step: float, calibration: float, sigma_dist_cm: float,
                        sigma_heading_deg: float) -> list[float]:
    """The standard deviations scaled with the step length (a rate per metre)."""
    r = step / calibration
    return [sigma_dist_cm / 100 * r, math.radians(sigma_heading_deg) * r]


def mistake_step_degrees(step: float, calibration: float, sigma_dist_cm: float,
                         sigma_heading_deg: float) -> list[float]:
    """The heading error left in degrees."""
    r = math.sqrt(step / calibration)
    return [sigma_dist_cm / 100 * r, sigma_heading_deg * r]


def mistake_step_calibration_value(step: float, calibration: float, sigma_dist_cm: float,
                                   sigma_heading_deg: float) -> list[float]:
    """The calibration drive's errors taken as the step's."""
    return [sigma_dist_cm / 100, math.radians(sigma_heading_deg)]


def mistake_step_centimetres(step: float, calibration: float, sigma_dist_cm: float,
                             sigma_heading_deg: float) -> list[float]:
    """The position uncertainty left in centimetres."""
    r = math.sqrt(step / calibration)
    return [sigma_dist_cm * r, math.radians(sigma_heading_deg) * r]


def odometry_accumulated(sigma_pos: float, sigma_theta: float, steps: int) -> list[float]:
    """``[σ_pos, σ_θ]`` after ``steps`` independent steps (random walk, ``σ √k``)."""
    return [cap.random_walk(sigma_pos, steps), cap.random_walk(sigma_theta, steps)]


def mistake_accumulated_linear(sigma_pos: float, sigma_theta: float, steps: int) -> list[float]:
    """Independent errors added like a bias: ``k σ`` instead of ``√k σ``."""
    return [sigma_pos * steps, sigma_theta * steps]


def mistake_accumulated_variance(sigma_pos: float, sigma_theta: float,
                                 steps: int) -> list[float]:
    """The variances ``k σ²`` given instead of the standard deviations."""
    return [sigma_pos**2 * steps, sigma_theta**2 * steps]


def lateral_drift(distance: float, heading_error_deg: float) -> float:
    """Sideways offset (m) after ``distance`` metres with a heading error in degrees."""
    return cap.lateral_drift(distance, math.radians(heading_error_deg))


def mistake_drift_degrees(distance: float, heading_error_deg: float) -> float:
    """``sin`` of the angle in degrees read as radians."""
    return cap.lateral_drift(distance, heading_error_deg)


def mistake_drift_cosine(distance: float, heading_error_deg: float) -> float:
    """The shortfall along the heading, ``d (1 − cos δθ)``, instead of the sideways offset."""
    return distance * (1 - math.cos(math.radians(heading_error_deg)))


# --- the LiDAR scan -------------------------------------------------------------------------


def scan_landmarks(fov_deg: float, resolution_deg: float, hit_fraction: float,
                   rays_per_landmark: float) -> list[float]:
    """``[valid readings, landmarks]`` per scan (expected values)."""
    valid = cap.scan_readings(fov_deg, resolution_deg, hit_fraction)
    return [valid, cap.landmarks_per_scan(valid, rays_per_landmark)]


def mistake_scan_all_rays(fov_deg: float, resolution_deg: float, hit_fraction: float,
                          rays_per_landmark: float) -> list[float]:
    """Every ray counted as a valid reading (the hit fraction ignored)."""
    rays = fov_deg / resolution_deg
    return [rays, rays / rays_per_landmark]


def mistake_scan_landmarks_from_rays(fov_deg: float, resolution_deg: float, hit_fraction: float,
                                     rays_per_landmark: float) -> list[float]:
    """Valid readings right, landmarks counted over all rays instead of the valid ones."""
    valid = cap.scan_readings(fov_deg, resolution_deg, hit_fraction)
    return [valid, fov_deg / resolution_deg / rays_per_landmark]


# --- memory ---------------------------------------------------------------------------------


def slam_memory(side: float, resolution: float, poses: int, landmarks: int,
                blocks_per_variable: int) -> list[float]:
    """``[grid (MB), graph (kB)]``: the int8 grid and the graph's mean plus sparse information
    blocks in doubles (1 MB = 10⁶ bytes, 1 kB = 10³ bytes)."""
    return [cap.grid_bytes(side, resolution, 1) / 1e6,
            cap.graph_bytes(poses, landmarks, blocks_per_variable) / 1e3]


def mistake_memory_dense(side: float, resolution: float, poses: int, landmarks: int,
                         blocks_per_variable: int) -> list[float]:
    """The information matrix stored dense (n² doubles) instead of as sparse blocks."""
    mean = cap.graph_dof(poses, landmarks) * cap.DOUBLE_BYTES
    return [cap.grid_bytes(side, resolution, 1) / 1e6,
            (mean + cap.dense_information_bytes(poses, landmarks)) / 1e3]


def mistake_memory_no_mean(side: float, resolution: float, poses: int, landmarks: int,
                           blocks_per_variable: int) -> list[float]:
    """The mean vector left out of the graph's memory."""
    mean = cap.graph_dof(poses, landmarks) * cap.DOUBLE_BYTES
    return [cap.grid_bytes(side, resolution, 1) / 1e6,
            (cap.graph_bytes(poses, landmarks, blocks_per_variable) - mean) / 1e3]


def mistake_memory_grid_not_squared(side: float, resolution: float, poses: int, landmarks: int,
                                    blocks_per_variable: int) -> list[float]:
    """One row of grid cells counted instead of the square."""
    return [round(side / resolution) / 1e6,
            cap.graph_bytes(poses, landmarks, blocks_per_variable) / 1e3]


# --- the time budget ------------------------------------------------------------------------


def _stages(t_odometry: float, t_features: float, t_association: float, t_loop: float,
            t_optimise: float, t_map: float) -> list[float]:
    return [t_odometry, t_features, t_association, t_loop, t_optimise, t_map]


def time_budget(rate_hz: float, t_odometry: float, t_features: float, t_association: float,
                t_loop: float, t_optimise: float, t_map: float) -> list[float]:
    """``[total (ms), headroom (ms)]`` of the per-frame pipeline at ``rate_hz``."""
    stages = _stages(t_odometry, t_features, t_association, t_loop, t_optimise, t_map)
    return list(cap.frame_headroom(rate_hz, stages))


def mistake_budget_per_second(rate_hz: float, t_odometry: float, t_features: float,
                              t_association: float, t_loop: float, t_optimise: float,
                              t_map: float) -> list[float]:
    """The headroom measured against a whole second instead of one frame period."""
    total = math.fsum(_stages(t_odometry, t_features, t_association, t_loop, t_optimise, t_map))
    return [total, 1000.0 - total]
