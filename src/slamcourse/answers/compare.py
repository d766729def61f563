"""Numeric comparison and formatting helpers shared by the numeric checkers.

Pure Python on floats and (nested) lists; arrays are accepted where noted through their
``tolist()`` method, so numpy is never imported here.

The tolerance rule of the course: an answer ``a`` matches the reference ``b`` when
``|a − b| ≤ atol + rtol·|b|``. :func:`is_close` is defined by :func:`tolerance_window`, so the
window shown to a learner and the decision always agree, edges included.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from dataclasses import dataclass, field
from typing import Any

from slamcourse.errors import GraderError

__all__ = [
    "EntryComparison",
    "angle_is_close",
    "compare_entries",
    "format_number",
    "format_window",
    "is_close",
    "tolerance_window",
    "wrap_angle",
]


def tolerance_window(expected: float, rtol: float, atol: float) -> tuple[float, float]:
    """The accepted interval ``[lo, hi]``: ``expected ± (atol + rtol·|expected|)``.

    >>> tolerance_window(10.0, 0.01, 0.0)
    (9.9, 10.1)
    """
    tol = atol + rtol * abs(expected)
    return expected - tol, expected + tol


def is_close(got: float, expected: float, rtol: float, atol: float) -> bool:
    """True when ``got`` lies in :func:`tolerance_window` (edges included); False if not finite."""
    if not math.isfinite(got):
        return False
    lo, hi = tolerance_window(expected, rtol, atol)
    return lo <= got <= hi


def wrap_angle(x: float) -> float:
    """``x`` plus a multiple of 2π, in (−π, π]: ``wrap_angle(3*pi/2) == -pi/2``; nan if infinite."""
    if not math.isfinite(x):
        return math.nan
    r = math.remainder(x, math.tau)  # exact, in [-pi, pi]
    if r <= -math.pi:
        r += math.tau
    return r


def angle_is_close(got: float, expected: float, rtol: float, atol: float) -> bool:
    """Angles compared modulo 2π: ``|wrap(got − expected)| ≤ atol + rtol·|wrap(expected)|``."""
    if not (math.isfinite(got) and math.isfinite(expected)):
        return False
    difference = abs(wrap_angle(got - expected))
    return difference <= atol + rtol * abs(wrap_angle(expected))


@dataclass(frozen=True)
class EntryComparison:
    """Entry-by-entry comparison of a vector or matrix answer with the reference.

    ``wrong`` holds the indices (``(i,)`` or ``(i, j)``, 0-based) of the entries outside their
    tolerance; it is empty when the shapes differ (then ``shape_ok`` is False).
    """

    shape_ok: bool
    got_shape: tuple[int, ...]
    expected_shape: tuple[int, ...]
    wrong: list[tuple[int, ...]] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """Shapes agree and every entry is within tolerance."""
        return self.shape_ok and not self.wrong


def _plain(x: Any) -> Any:
    tolist = getattr(x, "tolist", None)
    return tolist() if callable(tolist) else x


def _is_seq(x: Any) -> bool:
    return isinstance(x, list | tuple)


def _number(x: Any, what: str) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        raise GraderError(f"{what} holds {x!r}, which is not a number") from None


def _shape_and_flat(x: Any, what: str) -> tuple[tuple[int, ...], list[float]]:
    """Shape and row-major entries of a scalar, a 1-D or a rectangular 2-D sequence."""
    x = _plain(x)
    if not _is_seq(x):
        return (), [_number(x, what)]
    rows = [_plain(r) for r in x]
    if not any(_is_seq(r) for r in rows):
        return (len(rows),), [_number(r, what) for r in rows]
    if not all(_is_seq(r) for r in rows):
        raise GraderError(f"{what} mixes numbers and rows")
    lengths = {len(r) for r in rows}
    if len(lengths) != 1:
        raise GraderError(f"{what} has rows of different lengths {sorted(lengths)}")
    flat = [_plain(v) for r in rows for v in r]
    if any(_is_seq(v) for v in flat):
        raise GraderError(f"{what} has more than two dimensions")
    return (len(rows), lengths.pop()), [_number(v, what) for v in flat]


def _index(flat: int, shape: tuple[int, ...]) -> tuple[int, ...]:
    if len(shape) == 2:
        return divmod(flat, shape[1])
    if len(shape) == 1:
        return (flat,)
    return ()


def _angle_set(angle: Collection[int] | bool, size: int) -> set[int]:
    if isinstance(angle, bool):
        return set(range(size)) if angle else set()
    marked = set(angle)
    outside = sorted(i for i in marked if not 0 <= i < size)
    if outside:
        raise GraderError(f"angle indices {outside} are outside the {size} entries")
    return marked


def compare_entries(
    got: Any,
    expected: Any,
    rtol: float,
    atol: float,
    *,
    angle: Collection[int] | bool = (),
    exact: bool = False,
) -> EntryComparison:
    """Compare a vector or matrix (nested lists, tuples or arrays) entry by entry.

    ``angle=True`` compares every entry modulo 2π; a collection of flat (row-major) indices
    marks just those entries. ``exact=True`` demands equality (modulo 2π for angle entries).
    Rectangular input is required (a ragged reference or answer is a :class:`GraderError`;
    :func:`~slamcourse.answers.parse.parse_matrix` never returns one).
    """
    got_shape, got_flat = _shape_and_flat(got, "the answer")
    expected_shape, expected_flat = _shape_and_flat(expected, "the reference")
    angles = _angle_set(angle, len(expected_flat))
    if got_shape != expected_shape:
        return EntryComparison(False, got_shape, expected_shape, [])
    if exact:
        rtol = atol = 0.0
    wrong: list[tuple[int, ...]] = []
    for i, (a, b) in enumerate(zip(got_flat, expected_flat, strict=True)):
        close = angle_is_close if i in angles else is_close
        if not close(a, b, rtol, atol):
            wrong.append(_index(i, expected_shape))
    return EntryComparison(True, got_shape, expected_shape, wrong)


def _format(x: float, digits: int) -> str:
    x = float(x)
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if x == 0:
        return "0"
    if x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    if abs(x) < 1 or abs(x) >= 1e15:
        return f"{x:.{digits}g}"
    return f"{x:.{digits}f}".rstrip("0").rstrip(".")


def format_number(x: float) -> str:
    """Compact form for feedback and templates.

    Integers without decimals (``10609``); below 1 in size, 4 significant digits (``0.1419``,
    ``-0.09``), scientific when tiny (``1.42e-05``); from 1 up, at most 4 decimals, trimmed
    (``5``, ``2.5``, ``12.3457``); scientific from 1e15 (``1e+15``); ``nan``, ``inf``.
    """
    return _format(x, 4)


def format_about(x: float) -> str:
    """A number after "about": 3 significant digits, integers as integers (``32.9``, ``12400``,
    ``0.0919``)."""
    if not math.isfinite(x) or x == 0:
        return _format(x, 4)
    digits = 3 - 1 - math.floor(math.log10(abs(x)))
    rounded = round(x, digits)
    if rounded == int(rounded) and abs(rounded) < 1e15:
        return str(int(rounded))
    return _format(rounded, max(digits, 0) if digits > 0 else 4)


def plural(count: float, word: str, many: str | None = None) -> str:
    """``1 entry``, ``2 entries``, ``12403 entries``: the count (as an integer when it is one)
    and the word in the right number."""
    if many is None:
        consonant_y = word.endswith("y") and word[-2:-1] not in tuple("aeiou")
        many = word[:-1] + "ies" if consonant_y else word + "s"
    return f"{format_number(count)} {word if count == 1 else many}"


def format_window(lo: float, hi: float) -> str:
    """``[lo, hi]`` as :func:`format_number` writes them, more digits if they would look equal."""
    for digits in range(4, 18):
        a, b = _format(lo, digits), _format(hi, digits)
        if a != b or lo == hi:
            break
    return f"[{a}, {b}]"
