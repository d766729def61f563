"""Reference answers for chapter ``se2``: poses in the plane and how they combine.

A pose ``(x, y, θ)`` is in metres, metres and radians (counter-clockwise from the world's x
axis). ``a ⊕ b`` applies ``b`` in the frame of ``a``; ``a⁻¹`` undoes ``a``; ``between(a, b)``
is ``a⁻¹ ⊕ b``, pose ``b`` seen from pose ``a``. The mathematics lives in
:mod:`slamcourse.slam.se2`; this module adapts it to the exercises' parameters. Functions whose
name starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from slamcourse.slam import se2

Pose = Sequence[float]


# --- numeric exercises ------------------------------------------------------------------------


def wrapped(a: float) -> float:
    return se2.wrap_angle(a)


def mistake_wrap_zero_to_two_pi(a: float) -> float:
    """``a mod 2π``: the right direction, in [0, 2π) instead of (−π, π]."""
    return a % (2 * math.pi)


def composed(xa: float, ya: float, ta: float, xb: float, yb: float, tb: float) -> list[float]:
    return list(se2.compose((xa, ya, ta), (xb, yb, tb)))


def mistake_compose_added(
    xa: float, ya: float, ta: float, xb: float, yb: float, tb: float
) -> list[float]:
    """Components added: ``b``'s displacement not rotated into ``a``'s frame."""
    return [xa + xb, ya + yb, se2.wrap_angle(ta + tb)]


def mistake_compose_swapped(
    xa: float, ya: float, ta: float, xb: float, yb: float, tb: float
) -> list[float]:
    """``b ⊕ a`` instead of ``a ⊕ b``."""
    return list(se2.compose((xb, yb, tb), (xa, ya, ta)))


def inverted(x: float, y: float, t: float) -> list[float]:
    return list(se2.inverse((x, y, t)))


def mistake_inverse_negated(x: float, y: float, t: float) -> list[float]:
    """Every component negated: ``(−x, −y, −θ)``."""
    return [-x, -y, se2.wrap_angle(-t)]


def relative(xa: float, ya: float, ta: float, xb: float, yb: float, tb: float) -> list[float]:
    return list(se2.between((xa, ya, ta), (xb, yb, tb)))


def mistake_relative_world_frame(
    xa: float, ya: float, ta: float, xb: float, yb: float, tb: float
) -> list[float]:
    """The world-frame difference ``b − a``, not rotated into ``a``'s frame."""
    return [xb - xa, yb - ya, se2.wrap_angle(tb - ta)]


def mistake_relative_reversed(
    xa: float, ya: float, ta: float, xb: float, yb: float, tb: float
) -> list[float]:
    """Pose ``a`` seen from ``b`` (``b⁻¹ ⊕ a``) instead of ``b`` seen from ``a``."""
    return list(se2.between((xb, yb, tb), (xa, ya, ta)))


# --- code: wrap_angle -------------------------------------------------------------------------


def wrap_angle(a: float) -> float:
    return se2.wrap_angle(a)


def wrap_inputs() -> Any:
    """Angles in [−40, 40] rad, never within 1e-6 of an odd multiple of π (where methods that are
    all correct may round to either end) except ±π themselves, which the examples cover."""
    from hypothesis import strategies as st

    def clear_of_boundary(a: float) -> bool:
        return abs(math.remainder(a, 2 * math.pi)) < math.pi - 1e-6

    angle = st.floats(-40.0, 40.0, allow_nan=False, allow_infinity=False)
    return st.fixed_dictionaries({"a": angle.filter(clear_of_boundary)})


def mistake_wrap_none(a: float) -> float:
    """The angle returned as it came."""
    return a


def mistake_wrap_half_open_low(a: float) -> float:
    """Wrapped into [−π, π): ``π`` comes back as ``−π``."""
    return a - 2 * math.pi * math.floor((a + math.pi) / (2 * math.pi))


def mistake_wrap_modulo(a: float) -> float:
    """``a % 2π``: into [0, 2π)."""
    return a % (2 * math.pi)


def mistake_wrap_atan2(a: float) -> float:
    """``atan2(sin a, cos a)``: right everywhere except that ``−π`` stays ``−π``."""
    return math.atan2(math.sin(a), math.cos(a))


def mistake_wrap_once(a: float) -> float:
    """One correction of 2π at most: wrong for angles more than a turn away."""
    if a > math.pi:
        return a - 2 * math.pi
    if a <= -math.pi:
        return a + 2 * math.pi
    return a


# --- code: between ----------------------------------------------------------------------------


def between(a: Pose, b: Pose) -> list[float]:
    return list(se2.between(a, b))


def pose_pairs() -> Any:
    """Two poses: positions in [−20, 20] m, headings in [−π, π] rad."""
    from hypothesis import strategies as st

    coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
    heading = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
    pose = st.tuples(coord, coord, heading)
    return st.fixed_dictionaries({"a": pose, "b": pose})


def mistake_between_world_frame(a: Pose, b: Pose) -> list[float]:
    """``b − a`` in world coordinates: the offset is not rotated into ``a``'s frame."""
    return [b[0] - a[0], b[1] - a[1], se2.wrap_angle(b[2] - a[2])]


def mistake_between_reversed(a: Pose, b: Pose) -> list[float]:
    """``a`` seen from ``b``."""
    return list(se2.between(b, a))


def mistake_between_rotation_not_transposed(a: Pose, b: Pose) -> list[float]:
    """The offset rotated by ``+θ_a`` (``R``) instead of ``−θ_a`` (``Rᵀ``)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return [c * dx - s * dy, s * dx + c * dy, se2.wrap_angle(b[2] - a[2])]
