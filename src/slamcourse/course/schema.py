"""Strict key and type checks for course files; every problem names the line and the fix."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from slamcourse.course.yamlio import LineDict
from slamcourse.errors import Problem

_TYPE_NAMES = {
    str: "text",
    int: "a whole number",
    float: "a number",
    bool: "true or false",
    list: "a list",
    dict: "a mapping",
}


def suggest(word: str, known: Collection[str]) -> str:
    """`` — did you mean 'x'?`` for the nearest known word, or an empty string."""
    import difflib  # only when there is something to suggest

    close = difflib.get_close_matches(word, sorted(known), n=1, cutoff=0.6)
    return f"; did you mean '{close[0]}'?" if close else ""


class Checker:
    """Collects problems for one file so that loading can go on after the first one."""

    def __init__(self, path: str) -> None:
        self.path = path
        self.problems: list[Problem] = []

    def add(self, line: int | None, message: str) -> None:
        self.problems.append(Problem(self.path, line, message))

    def keys(
        self, data: LineDict, allowed: Collection[str], required: Collection[str], what: str
    ) -> None:
        """Report unknown keys (with the nearest known key) and missing required keys."""
        suggested = set()
        for key in data:
            if key not in allowed:
                import difflib

                close = difflib.get_close_matches(key, sorted(allowed), n=1, cutoff=0.6)
                suggested.update(close)
                self.add(
                    data.line_of(key),
                    f"unknown key '{key}' in {what}{suggest(key, allowed)}"
                    f" (known keys: {', '.join(sorted(allowed))})",
                )
        for key in required:
            if key not in data and key not in suggested:
                self.add(data.line, f"{what} is missing the required key '{key}'")

    def typed(
        self, data: LineDict, key: str, types: type | tuple[type, ...], default: Any = None
    ) -> Any:
        """``data[key]`` if it has one of ``types``; else report it and return ``default``."""
        if key not in data:
            return default
        value = data[key]
        types = types if isinstance(types, tuple) else (types,)
        ok = isinstance(value, types) and not (isinstance(value, bool) and bool not in types)
        if float in types and isinstance(value, int) and not isinstance(value, bool):
            ok = True
        if not ok:
            names = " or ".join(_TYPE_NAMES.get(t, t.__name__) for t in types)
            self.add(data.line_of(key), f"'{key}' must be {names}, not {value!r}")
            return default
        return value

    def distribution(
        self, item: LineDict, forms: dict[str, str], what: str
    ) -> tuple[str, tuple[Any, ...]] | None:
        """The one ``dist: argument`` entry of ``item`` (e.g. ``uniform: [-5, 5]``), checked
        against its form, or None (reported). ``forms`` maps each allowed key to ``range``
        (two numbers, low ≤ high), ``int-range`` (two whole numbers), ``list`` (non-empty),
        ``text`` or ``any``."""
        found = [d for d in forms if d in item]
        if len(found) != 1:
            self.add(
                item.line,
                f"{what} needs exactly one of {', '.join(forms)} "
                f"(found {', '.join(found) or 'none'})",
            )
            return None
        dist = found[0]
        arg, form, line = item[dist], forms[dist], item.line_of(dist)
        if form in ("range", "int-range"):
            number = int if form == "int-range" else (int, float)
            if (
                not isinstance(arg, list)
                or len(arg) != 2
                or not all(isinstance(a, number) and not isinstance(a, bool) for a in arg)
                or arg[0] > arg[1]
            ):
                kind = "whole numbers" if form == "int-range" else "numbers"
                self.add(line, f"'{dist}' of {what} must be [low, high], {kind} with low ≤ high")
                return None
            return dist, tuple(arg)
        if form == "list":
            if not isinstance(arg, list) or not arg:
                self.add(line, f"'{dist}' of {what} must be a non-empty list")
                return None
            return dist, tuple(arg)
        if form == "text" and not isinstance(arg, str):
            self.add(line, f"'{dist}' of {what} must be a formula written as text")
            return None
        return dist, (arg,)

    def mapping(self, value: Any, line: int, what: str) -> LineDict | None:
        if isinstance(value, LineDict):
            return value
        self.add(line, f"{what} must be a mapping of 'key: value' lines, not {value!r}")
        return None
