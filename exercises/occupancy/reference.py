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


def probability(l: float) -> float:  # noqa: E741 - l is the standard symbol
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
    """Hypothesis strategy for ``update_ray``: a row of 1–12 cells with log-odds in [−5, 5]
    (a list), a hit cell inside the row, ``l_occ`` in [0.1, 3] and ``l_free`` in [−3, −0.1]."""
    from hypothesis import strategies as st

    value = st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False)
    row = st.lists(value, min_size=1, max_size=12)
    return row.flatmap(lambda cells: st.fixed_dictionaries({
        "log_odds": st.just(cells),
        "hit_index": st.integers(0, len(cells) - 1),
        "l_occ": st.floats(0.1, 3.0, allow_nan=False, allow_infinity=False),
        "l_free": st.floats(-3.0, -0.1, allow_nan=False, allow_infinity=False),
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
