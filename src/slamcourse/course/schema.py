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

    def mapping(self, value: Any, line: int, what: str) -> LineDict | None:
        if isinstance(value, LineDict):
            return value
        self.add(line, f"{what} must be a mapping of 'key: value' lines, not {value!r}")
        return None
