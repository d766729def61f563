"""Hypothesis strategies for a code exercise's arguments (imported only when grading code)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from slamcourse.answers import compile_expression
from slamcourse.errors import AnswerFormatError


@dataclass(frozen=True)
class Argument:
    """One declared argument: ``dist`` is ``float``, ``int`` or ``choice``."""

    name: str
    dist: str
    args: tuple[Any, ...]
    line: int


def strategy_for(arguments: tuple[Argument, ...], assume: tuple[str, ...]) -> Any:
    """A strategy of keyword-argument dicts, filtered by the ``assume`` expressions."""
    from hypothesis import strategies as st  # imported here: loading an exercise must stay light

    fields: dict[str, Any] = {}
    for arg in arguments:
        if arg.dist == "float":
            fields[arg.name] = st.floats(
                float(arg.args[0]), float(arg.args[1]), allow_nan=False, allow_infinity=False
            )
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
