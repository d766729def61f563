"""Reference answers for chapter ``drift``: how dead-reckoning error accumulates.

A robot that integrates its own motion (odometry) adds a small error at every step. How those
errors add up depends on their nature:

- a systematic error (a bias ``b`` per step) adds linearly: ``b·k`` after ``k`` steps;
- independent zero-mean errors (standard deviation ``σ`` per step) add in quadrature: their
  variances add, so the standard deviation after ``k`` steps is ``σ·√k``;
- a heading bias rotates every later step, so the lateral error grows faster than linearly.

Every function takes the exercise's parameters as keyword arguments. Functions whose name starts
with ``mistake_`` (numeric exercises) or that are named in a code exercise's misconceptions
compute a named wrong answer.
"""

from __future__ import annotations

import math

import numpy as np

# --- systematic and random drift ------------------------------------------------------------


def systematic_drift(bias: float, steps: int) -> float:
    """Position error (m) after ``steps`` steps that each err by ``bias`` metres the same way."""
    return bias * steps


def random_walk_error(sigma: float, steps: int) -> float:
    """1σ position error (m) after ``steps`` independent steps of standard deviation ``sigma``:
    the variances add, ``k·σ²``, so the standard deviation is ``σ·√k``."""
    return sigma * math.sqrt(steps)


def random_walk_systematic(sigma: float, steps: int) -> float:
    """Wrong: ``σ·k``, the errors added as if they all pointed the same way."""
    return sigma * steps


def random_walk_variance(sigma: float, steps: int) -> float:
    """Wrong: ``σ²·k``, the variance (m²) where the standard deviation was asked for."""
    return sigma * sigma * steps


def mistake_random_walk_systematic(sigma: float, steps: int) -> float:
    """``σ·k`` (numeric exercise)."""
    return random_walk_systematic(sigma, steps)


def mistake_systematic_sqrt(bias: float, steps: int) -> float:
    """``b·√k``: a bias treated as if it were random noise."""
    return bias * math.sqrt(steps)


# --- the square loop ------------------------------------------------------------------------


def square_loop_error(bias: float, steps_per_side: int) -> float:
    """Closure error (m) of a square loop driven with a forward-only bias of ``bias`` m/step.

    Along each side the bias adds ``bias·steps_per_side`` metres in the direction of travel;
    the four directions are 0, π/2, π and 3π/2, and the error is the length of the vector sum.
    """
    error = np.zeros(2)
    for side in range(4):
        heading = side * math.pi / 2
        error += bias * steps_per_side * np.array([math.cos(heading), math.sin(heading)])
    return float(np.hypot(*error))


def mistake_square_loop_magnitudes(bias: float, steps_per_side: int) -> float:
    """``4·b·n``: the four sides' drifts added as lengths, ignoring their directions."""
    return 4 * bias * steps_per_side


def mistake_square_loop_one_side(bias: float, steps_per_side: int) -> float:
    """``b·n``: the drift of a single side."""
    return bias * steps_per_side


# --- heading drift --------------------------------------------------------------------------


def lateral_drift(step_length: float, heading_rate: float, steps: int) -> float:
    """Lateral error (m) of a robot meant to drive straight whose heading error grows by
    ``heading_rate`` rad per step: step ``k`` (1-based) is driven ``heading_rate·k`` off course
    and moves ``step_length·sin(heading_rate·k)`` sideways."""
    k = np.arange(1, steps + 1)
    return float(np.sum(step_length * np.sin(heading_rate * k)))


def lateral_drift_small_angle(step_length: float, heading_rate: float, steps: int) -> float:
    """Wrong: ``sin(x) ≈ x`` everywhere, i.e. ``Σ step·rate·k``."""
    return step_length * heading_rate * steps * (steps + 1) / 2


def lateral_drift_from_zero(step_length: float, heading_rate: float, steps: int) -> float:
    """Wrong: ``k = 0 … steps − 1``, the first step driven without heading error."""
    return lateral_drift(step_length, heading_rate, steps) - step_length * math.sin(
        heading_rate * steps
    )


def lateral_drift_final_heading(step_length: float, heading_rate: float, steps: int) -> float:
    """Wrong: the whole distance driven at the final heading error,
    ``steps·step·sin(rate·steps)``."""
    return steps * step_length * math.sin(heading_rate * steps)


# --- heading drift as a number, and the loop-closure correction ------------------------------
# (computed by the course's reference library, slamcourse.slam.drift)


def heading_drift_value(step_length: float, heading_rate: float, steps: int, **_: float) -> float:
    """Sideways error (m): ``Σ_{k=1..steps} step_length·sin(heading_rate·k)``."""
    from slamcourse.slam.drift import lateral_drift as drift

    return drift(step_length, heading_rate, int(steps))


def mistake_heading_small_angle(
    step_length: float, heading_rate: float, steps: int, **_: float
) -> float:
    """``sin x ≈ x`` for every step: ``step_length·heading_rate·steps(steps + 1)/2``."""
    return lateral_drift_small_angle(step_length, heading_rate, int(steps))


def mistake_heading_from_zero(
    step_length: float, heading_rate: float, steps: int, **_: float
) -> float:
    """``k = 0 … steps − 1``: the first step driven without heading error."""
    return lateral_drift_from_zero(step_length, heading_rate, int(steps))


def mistake_heading_final(step_length: float, heading_rate: float, steps: int, **_: float) -> float:
    """The whole distance at the final heading error: ``distance·sin(heading_rate·steps)``."""
    return lateral_drift_final_heading(step_length, heading_rate, int(steps))


def loop_pose_correction(num_steps: int, closure_error: float, pose: int) -> float:
    """How far (m) a least-squares loop closure moves pose ``pose`` of a 1-D loop of
    ``num_steps`` equally uncertain odometry steps whose closure disagrees by ``closure_error``
    (the loop-closure measurement exact, the start pose known): ``e·k/n``."""
    from slamcourse.slam.drift import loop_closure_correction

    return float(loop_closure_correction([1.0] * int(num_steps), closure_error)[int(pose)])


def mistake_correction_last_only(num_steps: int, closure_error: float, pose: int) -> float:
    """Only the last pose corrected: pose ``k < n`` does not move at all."""
    return 0.0


def mistake_correction_rigid(num_steps: int, closure_error: float, pose: int) -> float:
    """The whole trajectory shifted by the full error ``e`` (the known start pose moves too)."""
    return closure_error


def mistake_correction_one_share(num_steps: int, closure_error: float, pose: int) -> float:
    """``e/n``: one step's share, not the shares of all ``k`` steps before the pose."""
    return closure_error / num_steps


def square_loop_closure_error(bias: float, steps_per_side: int) -> float:
    """Closure error (m) of the square loop, by dead-reckoning both paths: the estimate drives
    unit steps, the robot really drives ``1 + bias``; both at headings 0, π/2, π, 3π/2."""
    from slamcourse.slam.drift import dead_reckoning

    n = int(steps_per_side)
    headings = np.repeat([0.0, math.pi / 2, math.pi, 3 * math.pi / 2], n)
    estimated = dead_reckoning(np.ones(4 * n), headings)[-1]
    true = dead_reckoning(np.full(4 * n, 1.0 + bias), headings)[-1]
    return float(np.hypot(*(true - estimated)))
