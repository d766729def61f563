"""Log-odds occupancy grids: the mathematics of chapter 8.

A cell's belief that it is occupied is stored as the log-odds ``l = ln(p / (1 − p))`` (0 for the
uninformed ``p = 0.5``). With a uniform prior, a reading that says "occupied with probability
``p_s``" adds ``ln(p_s / (1 − p_s))``; clamping keeps ``l`` inside ``[l_min, l_max]`` so that the
map can still follow a world that changes.
"""

from __future__ import annotations

import math
from collections.abc import Iterable


def log_odds(p: float) -> float:
    """``ln(p / (1 − p))`` of a probability ``0 < p < 1``."""
    return math.log(p / (1 - p))


def probability(l_cell: float) -> float:
    """The probability ``1 / (1 + e^{−l})`` of the log-odds ``l = l_cell``."""
    return 1 / (1 + math.exp(-l_cell))


def update(l_cell: float, sensor_prob: float) -> float:
    """``l + ln(p_s / (1 − p_s))``: one reading fused into a cell at ``l = l_cell``."""
    return l_cell + log_odds(sensor_prob)


def fuse(readings: Iterable[float], l0: float = 0.0) -> float:
    """Log-odds after fusing the readings (each a sensor probability) into a cell at ``l0``."""
    l_cell = l0
    for p in readings:
        l_cell = update(l_cell, p)
    return l_cell


def clamp(l_cell: float, l_min: float, l_max: float) -> float:
    """The log-odds ``l_cell`` limited to ``[l_min, l_max]``."""
    return min(max(l_cell, l_min), l_max)


def fuse_clamped(readings: Iterable[float], l_min: float, l_max: float, l0: float = 0.0) -> float:
    """Like :func:`fuse`, clamping after every reading."""
    l_cell = l0
    for p in readings:
        l_cell = clamp(update(l_cell, p), l_min, l_max)
    return l_cell


def readings_to_reach(l_start: float, l_target: float, sensor_prob: float) -> int:
    """Fewest identical readings ``sensor_prob`` that move a cell from ``l_start`` to at least
    ``l_target`` (towards occupied, ``sensor_prob > 0.5``) or to at most it (towards free)."""
    step = log_odds(sensor_prob)
    gap = l_target - l_start
    if gap == 0:
        return 0
    if step == 0 or (gap > 0) != (step > 0):
        raise ValueError("these readings move the cell away from the target")
    return math.ceil(gap / step)


def readings_to_flip(l_start: float, free_prob: float) -> int:
    """Fewest readings ``free_prob < 0.5`` that take an occupied cell (``l_start > 0``) strictly
    below ``l = 0``, i.e. to more likely free than occupied."""
    step = -log_odds(free_prob)
    return math.floor(l_start / step) + 1


def grid_cells(side: float, resolution: float, dims: int = 2) -> int:
    """Cells of a dense square (``dims = 2``) or cubic (``dims = 3``) grid, ``side`` metres
    across with cells ``resolution`` metres wide."""
    per_side = round(side / resolution)
    return math.prod([per_side] * dims)
