"""Ray casting on a grid (Bresenham) and the inverse sensor model along a beam: chapter 18.

Cells are integer pairs ``(x, y)`` (column, row) of a grid whose cells are one unit wide. A beam
from cell ``(x0, y0)`` to cell ``(x1, y1)`` crosses the cells of :func:`bresenham`: one per step
along the *major* axis (the one with the larger ``|Δ|``), the minor coordinate being the exact
line's value rounded to the nearest integer, **ties rounded up** (towards the larger
coordinate). Because the tie rule depends on the cell, not on the direction of travel, the
beam back from ``(x1, y1)`` crosses the same cells in reverse order.
"""

from __future__ import annotations

from collections.abc import Sequence

Cell = tuple[int, int]


def _round_half_up(num: int, den: int) -> int:
    """``⌊num/den + 1/2⌋`` for integers, ``den > 0``, exactly."""
    return (2 * num + den) // (2 * den)


def bresenham(x0: int, y0: int, x1: int, y1: int) -> list[Cell]:
    """Cells from ``(x0, y0)`` to ``(x1, y1)``, both included: ``max(|Δx|, |Δy|) + 1`` cells.

    8-connected (consecutive cells differ by at most 1 in each coordinate); exact integer
    arithmetic; ties rounded towards the larger minor coordinate.
    """
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [(x0, y0)]
    cells: list[Cell] = []
    for k in range(n + 1):
        if abs(dx) >= abs(dy):
            sx = 1 if dx > 0 else -1
            # the exact line at x = x0 + k·sx has y = y0 + k·dy/|dx|
            cells.append((x0 + k * sx, y0 + _round_half_up(k * dy, abs(dx))))
        else:
            sy = 1 if dy > 0 else -1
            cells.append((x0 + _round_half_up(k * dx, abs(dy)), y0 + k * sy))
    return cells


def beam_update(
    log_odds: Sequence[float], l_occ: float, l_free: float, hit: bool = True
) -> list[float]:
    """Inverse sensor model along one beam: ``log_odds`` lists the crossed cells in order.

    Cells before the last get ``+ l_free`` (< 0); the last gets ``+ l_occ`` (> 0) when the beam
    ended on an obstacle (``hit``), else ``+ l_free`` like the others (a max-range reading).
    """
    out = [v + l_free for v in log_odds]
    if hit and out:
        out[-1] = log_odds[-1] + l_occ
    return out


def log_odds_after_hits(l0: float, l_occ: float, k: int, l_max: float | None = None) -> float:
    """A cell's log-odds after ``k`` hits of ``+ l_occ`` each, clamped at ``l_max`` if given."""
    value = l0
    for _ in range(k):
        value += l_occ
        if l_max is not None:
            value = min(value, l_max)
    return value
