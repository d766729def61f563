"""Drift: how dead-reckoning error accumulates, and how a loop closure spreads its correction.

A robot that integrates its own motion (odometry) adds a small error at every step, and nothing
in odometry removes one. How the errors add up depends on their nature:

- a systematic error (a bias ``b`` metres per step, always the same way) adds linearly:
  ``b·k`` after ``k`` steps;
- independent zero-mean errors (standard deviation ``σ`` metres per step) add in quadrature:
  the variances add, ``k·σ²``, so the standard deviation is ``σ·√k``;
- a heading error rotates every later step, so the position error it causes keeps growing with
  the distance driven after it.

Positions are metres in the world frame, headings radians counter-clockwise from the x axis.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "dead_reckoning",
    "lateral_drift",
    "loop_closure_correction",
    "random_walk_sigma",
    "systematic_drift",
]


def systematic_drift(bias: float, steps: int) -> float:
    """Position error (m) after ``steps`` steps that each err by ``bias`` metres the same way."""
    return bias * steps


def random_walk_sigma(sigma: float, steps: int) -> float:
    """1σ position error (m) after ``steps`` independent steps of standard deviation ``sigma``
    (m): the variances add, ``k·σ²``."""
    return sigma * math.sqrt(steps)


def dead_reckoning(step_lengths: ArrayLike, headings: ArrayLike) -> NDArray[np.float64]:
    """Positions (shape ``(n + 1, 2)``, metres) of a robot starting at the origin that drives
    step ``k`` (``k = 0 … n − 1``) ``step_lengths[k]`` metres at heading ``headings[k]`` (rad)."""
    lengths = np.asarray(step_lengths, dtype=float)
    theta = np.asarray(headings, dtype=float)
    steps = np.stack([lengths * np.cos(theta), lengths * np.sin(theta)], axis=1)
    return np.vstack([np.zeros((1, 2)), np.cumsum(steps, axis=0)])


def lateral_drift(step_length: float, heading_rate: float, steps: int) -> float:
    """Sideways error (m) of a robot meant to drive straight along x whose heading error grows by
    ``heading_rate`` rad per step: step ``k = 1 … steps`` is driven at ``heading_rate·k``, so the
    error is ``Σ step_length·sin(heading_rate·k)``, the y of :func:`dead_reckoning`'s last point."""
    headings = heading_rate * np.arange(1, steps + 1)
    return float(dead_reckoning(np.full(steps, step_length), headings)[-1, 1])


def loop_closure_correction(
    odometry_variances: Sequence[float], closure_error: float, loop_variance: float = 0.0
) -> NDArray[np.float64]:
    """How far the least-squares solution moves each pose of a 1-D loop (shape ``(n + 1,)``, m).

    Poses ``x_0 … x_n``; ``x_0`` is known exactly, odometry step ``k`` (``x_{k−1} → x_k``) has
    variance ``odometry_variances[k − 1]`` (m²), and a loop closure measures ``x_n − x_0`` with
    variance ``loop_variance`` (m²), disagreeing with dead reckoning by ``closure_error`` (m).
    Pose ``k`` moves by its share of the accumulated uncertainty,

        δ_k = e · V_k / (V_n + σ_loop²),    V_k = Σ_{i ≤ k} σ_i²,

    so ``δ_0 = 0``, the correction grows along the loop, and with an exact closure the last pose
    absorbs the whole error. (This is the solution of the graph's normal equations; see
    :func:`slamcourse.slam.graph.solve`.)
    """
    variances = np.asarray(odometry_variances, dtype=float)
    accumulated = np.concatenate([[0.0], np.cumsum(variances)])
    correction: NDArray[np.float64] = (
        closure_error * accumulated / (accumulated[-1] + loop_variance)
    )
    return correction
