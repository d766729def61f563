"""Rendering prompts, hints, explanations and messages (Jinja2, imported only when needed)."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from functools import lru_cache
from typing import Any

from slamcourse.answers.compare import format_number
from slamcourse.course.model import ExerciseSpec, Text
from slamcourse.errors import CourseError, Problem


def num(value: Any, decimals: int | None = None) -> str:
    """A number written compactly; ``decimals`` fixes the number of decimals."""
    value = _plain(value)
    if isinstance(value, list | tuple):
        return vec(value, decimals)
    if decimals is not None:
        return f"{float(value):.{decimals}f}"
    return format_number(float(value))


def angle(value: Any) -> str:
    """An angle in radians: ``π/4``, ``-3π/2`` when it is a simple multiple of π, else a number."""
    value = float(_plain(value))
    for den in (1, 2, 3, 4, 6, 8, 12):
        k = value * den / math.pi
        if abs(k - round(k)) < 1e-9 and round(k) != 0:
            k = round(k)
            sign = "-" if k < 0 else ""
            k = abs(k)
            top = "π" if k == 1 else f"{k}π"
            return f"{sign}{top}" if den == 1 else f"{sign}{top}/{den}"
    return format_number(value)


def vec(values: Any, decimals: int | None = None) -> str:
    return "[" + ", ".join(num(v, decimals) for v in _plain(values)) + "]"


def mat(rows: Any, decimals: int | None = None) -> str:
    body = r" \\ ".join(" & ".join(num(v, decimals) for v in row) for row in _plain(rows))
    return r"\begin{bmatrix} " + body + r" \end{bmatrix}"


def _plain(value: Any) -> Any:
    tolist = getattr(value, "tolist", None)
    return tolist() if callable(tolist) else value


@lru_cache(maxsize=1)
def _environment() -> Any:
    import jinja2

    env = jinja2.Environment(
        undefined=jinja2.StrictUndefined, autoescape=False, keep_trailing_newline=False
    )
    env.filters.update(num=num, angle=angle, vec=vec, mat=mat)
    return env


@lru_cache(maxsize=512)
def _compile(source: str) -> Any:
    return _environment().from_string(source)


_SUBSTITUTION = re.compile(
    r"\{\{\s*([A-Za-z_][A-Za-z0-9_]*)\s*(?:\|\s*(num|angle|vec|mat)\s*(?:\(\s*(\d+)\s*\))?\s*)?\}\}"
)
_FILTERS: dict[str, Callable[..., str]] = {"num": num, "angle": angle, "vec": vec, "mat": mat}


def substitute(source: str, context: dict[str, Any]) -> str | None:
    """Render a template made only of ``{{ name }}`` and ``{{ name | filter(n) }}`` without
    loading Jinja2 (most prompts are exactly that); ``None`` when Jinja2 is needed: any other
    tag, expression or filter, or a name the context lacks (Jinja2 then reports it)."""
    if "{%" in source or "{#" in source:
        return None
    out: list[str] = []
    pos = 0
    for match in _SUBSTITUTION.finditer(source):
        name, filt, arg = match.groups()
        if "{{" in source[pos : match.start()] or name not in context:
            return None
        value = context[name]
        if filt is None:
            text = str(value)
        elif arg is None:
            text = _FILTERS[filt](value)
        elif filt == "angle":  # angle takes no argument: let Jinja2 report it
            return None
        else:
            text = _FILTERS[filt](value, int(arg))
        out.append(source[pos : match.start()])
        out.append(text)
        pos = match.end()
    if "{{" in source[pos:]:
        return None
    out.append(source[pos:])
    return "".join(out)


def render(spec: ExerciseSpec, text: Text, context: dict[str, Any]) -> str:
    """Render ``text`` from ``spec``; a template error is a :class:`CourseError` at its line."""
    if "{" not in text.source:  # plain text needs no template engine
        return text.source.strip()
    try:
        fast = substitute(text.source, context)
    except (TypeError, ValueError):  # a filter given the wrong kind of value: let Jinja2 say so
        fast = None
    if fast is not None:
        return fast.strip()
    import jinja2

    from slamcourse.errors import relpath

    try:
        return str(_compile(text.source).render(**context)).strip()
    except jinja2.TemplateError as exc:
        offset = (getattr(exc, "lineno", None) or 1) - 1
        raise CourseError(
            Problem(
                relpath(spec.path, spec.course_root), text.line + offset, f"template error: {exc}"
            )
        ) from None
    except (TypeError, ValueError) as exc:  # a filter given the wrong kind of value
        raise CourseError(
            Problem(relpath(spec.path, spec.course_root), text.line, f"template error: {exc}")
        ) from None
