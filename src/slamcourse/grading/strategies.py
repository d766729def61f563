"""Hypothesis strategies for a code exercise's arguments (imported only when grading code).

Inputs come only from the physical range an exercise declares, in realistic magnitudes:

- floats are never NaN, never infinite and never subnormal;
- a float whose magnitude is below the range's *resolution* is drawn as ``0.0`` when the range
  contains 0 (the resolution is ``1e-9``, or a millionth of the range's largest bound when that
  is smaller, so a range declared in micro-units keeps its own scale);
- every float is rounded to 12 significant digits (and stays inside the declared range).

A position of ``3e-308`` metres or an angle of ``5e-324`` radians is not an input any learner's
correct code must survive: such values only test floating-point underflow (e.g. in
``cmath.exp``), not the mathematics the exercise asks for. Strategies written in reference.py
should draw their floats with :func:`real` to follow the same rule.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from slamcourse.answers import compile_expression
from slamcourse.errors import AnswerFormatError

SIGNIFICANT_DIGITS = 12
RESOLUTION = 1e-9


@dataclass(frozen=True)
class Argument:
    """One declared argument: ``dist`` is ``float``, ``int`` or ``choice``."""

    name: str
    dist: str
    args: tuple[Any, ...]
    line: int


def realistic(x: float, low: float, high: float) -> float:
    """``x`` (drawn from ``[low, high]``) with the rule of this module applied: tiny magnitudes
    become 0 when the range holds 0, then 12 significant digits, clamped to the range."""
    scale = max(abs(low), abs(high))
    resolution = min(RESOLUTION, scale * 1e-6) if scale > 0 else 0.0
    if low <= 0.0 <= high and abs(x) < resolution:
        return 0.0
    rounded = float(f"{x:.{SIGNIFICANT_DIGITS}g}")
    return min(max(rounded, low), high) + 0.0  # + 0.0 turns -0.0 into 0.0


def real(low: float, high: float) -> Any:
    """A strategy of realistic floats in ``[low, high]`` (for strategies in reference.py)."""
    from hypothesis import strategies as st

    low, high = float(low), float(high)
    return st.floats(low, high, allow_nan=False, allow_infinity=False, allow_subnormal=False).map(
        lambda x: realistic(x, low, high)
    )


def strategy_for(arguments: tuple[Argument, ...], assume: tuple[str, ...]) -> Any:
    """A strategy of keyword-argument dicts, filtered by the ``assume`` expressions."""
    from hypothesis import strategies as st  # imported here: loading an exercise must stay light

    fields: dict[str, Any] = {}
    for arg in arguments:
        if arg.dist == "float":
            fields[arg.name] = real(arg.args[0], arg.args[1])
        elif arg.dist == "int":
            fields[arg.name] = st.integers(int(arg.args[0]), int(arg.args[1]))
        else:
            fields[arg.name] = st.sampled_from(list(arg.args))
    strategy = st.fixed_dictionaries(fields)
    if assume:
        checks = [
            compile_expression(text, [a.name for a in arguments], logic=True) for text in assume
        ]
        strategy = strategy.filter(lambda kw: _holds(checks, kw))
    return strategy


def _holds(checks: list[Any], kwargs: dict[str, Any]) -> bool:
    try:
        return all(c.evaluate(kwargs) for c in checks)
    except AnswerFormatError:  # e.g. a division by zero inside the condition: not satisfied
        return False
