"""Reference code for chapter ``occupancy``: log-odds occupancy grids.

A cell's belief that it is occupied is the probability ``p``; the grid stores its log-odds
``l = log(p / (1 − p))`` (natural logarithm), with ``l = 0`` for the uninformed ``p = 0.5``.
A sensor reading that says "occupied with probability ``p_s``" is fused by adding
``log(p_s / (1 − p_s))`` to ``l`` (with a uniform prior, as here); the probability is recovered
with the logistic function ``p = 1 / (1 + e^{−l})``.

Every exercise function takes the exercise's parameters (or a code exercise's arguments) as
keyword arguments. Functions whose name starts with ``mistake_`` are wrong implementations or
wrong answers of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any


def log_odds(p: float) -> float:
    """``log(p / (1 − p))`` (natural log) of a probability ``0 < p < 1``."""
    return math.log(p / (1 - p))


def probability(l: float) -> float:
    """The probability ``1 / (1 + e^{−l})`` of the log-odds ``l``."""
    return 1 / (1 + math.exp(-l))


# --- one update -----------------------------------------------------------------------------


def log_odds_update(current_log_odds: float, sensor_prob: float) -> tuple[float, float]:
    """``(l′, p′)`` after fusing one reading: ``l′ = l + log(p_s/(1 − p_s))``, ``p′ = σ(l′)``."""
    new = current_log_odds + log_odds(sensor_prob)
    return new, probability(new)


def mistake_update_log_p(current_log_odds: float, sensor_prob: float) -> tuple[float, float]:
    """``log(p_s)`` added instead of the log-odds ``log(p_s/(1 − p_s))``."""
    new = current_log_odds + math.log(sensor_prob)
    return new, probability(new)


def mistake_update_multiplied(current_log_odds: float, sensor_prob: float) -> tuple[float, float]:
    """The probabilities multiplied, ``p′ = p · p_s``, and converted back to log-odds."""
    p = probability(current_log_odds) * sensor_prob
    return log_odds(p), p


def mistake_update_unnormalised(current_log_odds: float,
                                sensor_prob: float) -> tuple[float, float]:
    """Right log-odds, but the probability given as ``e^{l′}`` (the odds, not a probability)."""
    new = current_log_odds + log_odds(sensor_prob)
    return new, math.exp(new)


# --- updating the cells along one ray -------------------------------------------------------


def update_ray(log_odds: Sequence[float], hit_index: int, l_occ: float,
               l_free: float) -> list[float]:
    """Cells ``0 … hit_index − 1`` (the beam passed through) get ``+l_free``; the cell
    ``hit_index`` (where the beam ended) gets ``+l_occ``; cells beyond are unchanged."""
    out = list(log_odds)
    for k in range(hit_index):
        out[k] += l_free
    out[hit_index] += l_occ
    return out


def ray_inputs() -> Any:
    """Hypothesis strategy for ``update_ray``: a row of 1–60 cells (a 30 m beam through 0.5 m
    cells) with log-odds in [−10, 10], as floats or, in a quarter of the draws, as whole numbers
    in [−3, 3] (a freshly initialised map holds integer zeros); a hit cell inside the row;
    ``l_occ`` in [0.2, 6.9] and ``l_free`` in [−6.9, −0.2] (inverse sensor models from
    p = 0.55 to 0.999)."""
    from hypothesis import strategies as st

    value = st.floats(-10.0, 10.0, allow_nan=False, allow_infinity=False)
    floats = st.lists(value, min_size=1, max_size=60)
    whole = st.lists(st.integers(-3, 3), min_size=1, max_size=60)
    row = st.one_of(floats, floats, floats, whole)
    return row.flatmap(lambda cells: st.fixed_dictionaries({
        "log_odds": st.just(cells),
        "hit_index": st.integers(0, len(cells) - 1),
        "l_occ": st.floats(0.2, 6.9, allow_nan=False, allow_infinity=False),
        "l_free": st.floats(-6.9, -0.2, allow_nan=False, allow_infinity=False),
    }))


def mistake_ray_beyond_free(log_odds: Sequence[float], hit_index: int, l_occ: float,
                            l_free: float) -> list[float]:
    """Every cell except the hit marked free, including those behind the obstacle."""
    out = [v + l_free for v in log_odds]
    out[hit_index] = log_odds[hit_index] + l_occ
    return out


def mistake_ray_hit_not_updated(log_odds: Sequence[float], hit_index: int, l_occ: float,
                                l_free: float) -> list[float]:
    """The free cells updated, the hit cell left unchanged."""
    out = list(log_odds)
    for k in range(hit_index):
        out[k] += l_free
    return out


def mistake_ray_hit_as_free(log_odds: Sequence[float], hit_index: int, l_occ: float,
                            l_free: float) -> list[float]:
    """Off by one: the hit cell marked free as well (``range(hit_index + 1)``), never occupied."""
    out = list(log_odds)
    for k in range(hit_index + 1):
        out[k] += l_free
    return out


def mistake_ray_overwritten(log_odds: Sequence[float], hit_index: int, l_occ: float,
                            l_free: float) -> list[float]:
    """The cells set to ``l_free`` / ``l_occ`` instead of having them added."""
    out = list(log_odds)
    for k in range(hit_index):
        out[k] = l_free
    out[hit_index] = l_occ
    return out


# --- numeric exercises ----------------------------------------------------------------------


def log_odds_of(p: float) -> float:
    """``log(p / (1 − p))`` for the exercise parameter ``p``."""
    return log_odds(p)


def mistake_log_odds_log10(p: float) -> float:
    """Base-10 logarithm instead of the natural one."""
    return math.log10(p / (1 - p))


def mistake_log_odds_log_p(p: float) -> float:
    """``log p``: the log of the probability, not of the odds."""
    return math.log(p)


def mistake_log_odds_odds(p: float) -> float:
    """``p / (1 − p)``: the odds, logarithm not taken."""
    return p / (1 - p)


def two_readings(p1: float, p2: float) -> list[float]:
    """``[l, p]`` after fusing readings ``p1`` then ``p2`` into an uninformed cell (l = 0)."""
    l1, _ = log_odds_update(0.0, p1)
    return list(log_odds_update(l1, p2))


def mistake_two_readings_averaged(p1: float, p2: float) -> list[float]:
    """The two probabilities averaged."""
    p = (p1 + p2) / 2
    return [log_odds(p), p]


def mistake_two_readings_multiplied(p1: float, p2: float) -> list[float]:
    """The two probabilities multiplied."""
    p = p1 * p2
    return [log_odds(p), p]


def readings_needed(sensor_prob: float, target: float) -> int:
    """Fewest identical readings ``sensor_prob`` that take a cell from l = 0 to at least
    ``target``: ``⌈logit(target) / logit(sensor_prob)⌉``."""
    return math.ceil(log_odds(target) / log_odds(sensor_prob))


def mistake_readings_floor(sensor_prob: float, target: float) -> int:
    """Rounded down: the cell then stays just below the target."""
    return math.floor(log_odds(target) / log_odds(sensor_prob))


def mistake_readings_odds_ratio(sensor_prob: float, target: float) -> int:
    """The odds divided instead of the log-odds, as if each reading added its odds."""
    return math.ceil((target / (1 - target)) / (sensor_prob / (1 - sensor_prob)))


def grid_megabytes(side: float, resolution: float, bytes_per_cell: float) -> float:
    """Memory of a square grid ``side × side`` metres with cells ``resolution`` metres wide, in
    megabytes (10⁶ bytes)."""
    cells_per_side = round(side / resolution)
    return cells_per_side**2 * bytes_per_cell / 1e6


def mistake_grid_not_squared(side: float, resolution: float, bytes_per_cell: float) -> float:
    """Only one row of cells counted."""
    return round(side / resolution) * bytes_per_cell / 1e6


def mistake_grid_kilobytes(side: float, resolution: float, bytes_per_cell: float) -> float:
    """Bytes divided by 1000 only once (kilobytes reported as megabytes)."""
    return grid_megabytes(side, resolution, bytes_per_cell) * 1000


# --- contrary readings, clamping, 3D grids (these call ``slamcourse.slam.occupancy``) -------

from slamcourse.slam import occupancy as _occ  # noqa: E402


def back_to_even(p1: float, p2: float,
                 **_derived: float) -> int:
    """After one reading ``p1`` and one ``p2`` (from l = 0, ending at l > 0): the number of further
    readings ``p2`` that bring the cell back to ``p ≤ 0.5``."""
    return _occ.readings_to_reach(_occ.fuse([p1, p2]), 0.0, p2)


def mistake_back_to_even_first_free_ignored(p1: float, p2: float,
                                            **_derived: float) -> int:
    """The first contrary reading forgotten: ``⌈logit(p1) / |logit(p2)|⌉`` from the occupied
    reading alone (the classic 2.6 → 3 slip)."""
    return _occ.readings_to_reach(_occ.fuse([p1]), 0.0, p2)


def mistake_back_to_even_floor(p1: float, p2: float,
                               **_derived: float) -> int:
    """Rounded down: the cell is then still just above 0.5."""
    return math.floor(_occ.fuse([p1, p2]) / -_occ.log_odds(p2))


def mistake_back_to_even_cancel(p1: float, p2: float,
                                **_derived: float) -> int:
    """Readings assumed to cancel one for one: one occupied and one free are already even."""
    return 0


def unclamped_flip(n_occ: int, p_occ: float, p_free: float,
                   **_derived: float) -> int:
    """Readings ``p_free`` that take a cell seen ``n_occ`` times as ``p_occ`` (from l = 0, no
    clamping) strictly below l = 0."""
    return _occ.readings_to_flip(_occ.fuse([p_occ] * n_occ), p_free)


def mistake_flip_symmetric(n_occ: int, p_occ: float, p_free: float,
                           **_derived: float) -> int:
    """"As many contrary readings as supporting ones": true only when logit(p_free) =
    −logit(p_occ)."""
    return n_occ


def mistake_flip_floor(n_occ: int, p_occ: float, p_free: float,
                       **_derived: float) -> int:
    """``⌊l / |l_free|⌋``: the cell is then still (barely) occupied."""
    return math.floor(_occ.fuse([p_occ] * n_occ) / -_occ.log_odds(p_free))


def clamped_flip(n_occ: int, p_occ: float, p_free: float, l_max: float,
                 **_derived: float) -> int:
    """Like :func:`unclamped_flip`, with the log-odds clamped to ``[−l_max, l_max]``."""
    l = _occ.fuse_clamped([p_occ] * n_occ, -l_max, l_max)
    return _occ.readings_to_flip(l, p_free)


def mistake_clamped_flip_ignored(n_occ: int, p_occ: float, p_free: float, l_max: float,
                                 **_derived: float) -> int:
    """The clamp ignored: as many readings as for the unclamped cell."""
    return unclamped_flip(n_occ, p_occ, p_free)


def mistake_clamped_flip_floor(n_occ: int, p_occ: float, p_free: float, l_max: float,
                               **_derived: float) -> int:
    """``⌊l_max / |l_free|⌋``: the cell is then still (barely) occupied."""
    return math.floor(l_max / -_occ.log_odds(p_free))


def grid_3d_terabytes(side: float, resolution: float, bytes_per_cell: float) -> float:
    """Memory (TB, 10¹² bytes) of a dense cubic grid ``side`` metres on each edge."""
    return _occ.grid_cells(side, resolution, 3) * bytes_per_cell / 1e12


def mistake_grid_3d_squared(side: float, resolution: float, bytes_per_cell: float) -> float:
    """A 2D grid's cell count (squared, not cubed)."""
    return _occ.grid_cells(side, resolution, 2) * bytes_per_cell / 1e12


def mistake_grid_3d_gigabytes(side: float, resolution: float, bytes_per_cell: float) -> float:
    """The size in gigabytes reported as terabytes."""
    return grid_3d_terabytes(side, resolution, bytes_per_cell) * 1000


# --- the domain the prompt states (``valid:`` of update_ray) ----------------------------------


def ray_valid(log_odds: Sequence[float], hit_index: int, l_occ: float, l_free: float) -> bool:
    """``update_ray``'s domain: a row of 1–60 cells with log-odds in [−10, 10], a hit cell in
    the row, ``l_occ`` in [0.2, 6.9] and ``l_free`` in [−6.9, −0.2]."""
    if not 1 <= len(log_odds) <= 60 or not 0 <= hit_index < len(log_odds):
        return False
    return all(-10 <= v <= 10 for v in log_odds) and 0.2 <= l_occ <= 6.9 and -6.9 <= l_free <= -0.2


# --- a prior other than one half (issue 16) ---------------------------------------------------


def _logit(p: float) -> float:
    return math.log(p / (1 - p))


def _pair(log_odds: float) -> list[float]:
    """``[l, p]``: log-odds and the probability it stands for."""
    return [log_odds, 1 / (1 + math.exp(-log_odds))]


def prior_update(p0: float, p1: float, p2: float, **_derived: float) -> list[float]:
    """``[l, p]`` after two readings with inverse-sensor-model outputs ``p1``, ``p2`` from a
    prior ``p0``: ``l = l₀ + (logit p₁ − l₀) + (logit p₂ − l₀)``."""
    l0 = _logit(p0)
    return _pair(l0 + (_logit(p1) - l0) + (_logit(p2) - l0))


def prior_update_bayes(p0: float, p1: float, p2: float) -> float:
    """The probability by Bayes' rule on odds, no logarithm: each reading's likelihood ratio
    ``p(z|m)/p(z|¬m)`` is its posterior odds over the prior odds."""
    prior_odds = p0 / (1 - p0)
    odds = prior_odds
    for p in (p1, p2):
        odds *= (p / (1 - p)) / prior_odds
    return odds / (1 + odds)


def mistake_prior_not_subtracted(p0: float, p1: float, p2: float, **_derived: float) -> list[float]:
    """``l = l₀ + logit p₁ + logit p₂``: the prior counted three times."""
    return _pair(_logit(p0) + _logit(p1) + _logit(p2))


def mistake_prior_ignored(p0: float, p1: float, p2: float, **_derived: float) -> list[float]:
    """``l = logit p₁ + logit p₂``: started from 0 as if the prior were one half."""
    return _pair(_logit(p1) + _logit(p2))


def mistake_prior_start_zero(p0: float, p1: float, p2: float, **_derived: float) -> list[float]:
    """Started from ``l = 0`` but subtracted ``l₀`` at each reading: the prior removed once
    too often."""
    l0 = _logit(p0)
    return _pair(_logit(p1) - l0 + _logit(p2) - l0)
