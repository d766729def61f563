"""YAML loading that remembers line numbers, so every problem can be reported as ``path:line``.

Mappings load as :class:`LineDict` (a ``dict`` that knows the line of each key) and sequences as
:class:`LineList`. Duplicate keys, which PyYAML would silently overwrite, are reported.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from slamcourse.errors import CourseError, Problem

try:  # the C parser is several times faster; fall back to pure Python where libyaml is missing
    _Base: type = yaml.CSafeLoader
except AttributeError:  # pragma: no cover - depends on how PyYAML was built
    _Base = yaml.SafeLoader


class LineDict(dict[str, Any]):
    """A mapping from YAML with ``line`` (its own first line) and ``key_lines`` (per key)."""

    line: int = 0
    key_lines: dict[str, int]
    value_lines: dict[str, int]
    block_keys: set[str]

    def line_of(self, key: str) -> int:
        """The 1-based line of ``key`` (or of the mapping itself when the key is absent)."""
        return self.key_lines.get(key, self.line)

    def text_line(self, key: str) -> int:
        """The line where the *text* of a string value starts (block scalars start below)."""
        start = self.value_lines.get(key, self.line_of(key))
        return start + 1 if key in self.block_keys else start


class LineList(list[Any]):
    """A sequence from YAML with ``line`` and the line of each item."""

    line: int = 0
    item_lines: list[int]

    def line_of(self, index: int) -> int:
        return self.item_lines[index] if 0 <= index < len(self.item_lines) else self.line


class _Loader(_Base):  # type: ignore[misc]
    def __init__(self, stream: str, path: str) -> None:
        super().__init__(stream)
        self.path = path
        self.problems: list[Problem] = []


def _construct_map(loader: _Loader, node: yaml.MappingNode) -> LineDict:
    data = LineDict()
    data.line = node.start_mark.line + 1
    data.key_lines, data.value_lines, data.block_keys = {}, {}, set()
    loader.flatten_mapping(node)
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        line = key_node.start_mark.line + 1
        if not isinstance(key, str):
            key = str(key)
        if key in data:
            loader.problems.append(
                Problem(
                    loader.path,
                    line,
                    f"duplicate key '{key}' (first at line "
                    f"{data.key_lines[key]}); remove one of them",
                )
            )
        data[key] = loader.construct_object(value_node, deep=True)
        data.key_lines[key] = line
        data.value_lines[key] = value_node.start_mark.line + 1
        if isinstance(value_node, yaml.ScalarNode) and value_node.style in ("|", ">"):
            data.block_keys.add(key)
    return data


def _construct_seq(loader: _Loader, node: yaml.SequenceNode) -> LineList:
    data = LineList(loader.construct_object(child, deep=True) for child in node.value)
    data.line = node.start_mark.line + 1
    data.item_lines = [child.start_mark.line + 1 for child in node.value]
    return data


_Loader.add_constructor("tag:yaml.org,2002:map", _construct_map)
_Loader.add_constructor("tag:yaml.org,2002:seq", _construct_seq)


def load_yaml(text: str, path: str | Path, *, first_line: int = 1) -> Any:
    """Parse ``text`` (from ``path``); raise :class:`CourseError` for syntax errors or duplicates.

    ``first_line`` shifts reported lines when ``text`` is a fragment (e.g. front matter).
    """
    loader = _Loader(text, str(path))
    try:
        data = loader.get_single_data()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + first_line if mark else None
        raise CourseError(
            Problem(
                str(path),
                line,
                f"YAML syntax error: {exc.problem or exc.context}; check "
                "indentation and quote strings that contain ': ' or start with a symbol",
            )
        ) from None
    except yaml.YAMLError as exc:
        raise CourseError(Problem(str(path), None, f"YAML error: {exc}")) from None
    finally:
        loader.dispose()
    if first_line != 1:
        _shift(data, first_line - 1)
        for i, p in enumerate(loader.problems):
            loader.problems[i] = Problem(p.path, (p.line or 0) + first_line - 1, p.message)
    if loader.problems:
        raise CourseError(loader.problems)
    return data


def _shift(data: Any, by: int) -> None:
    if isinstance(data, LineDict):
        data.line += by
        data.key_lines = {k: v + by for k, v in data.key_lines.items()}
        data.value_lines = {k: v + by for k, v in data.value_lines.items()}
        for value in data.values():
            _shift(value, by)
    elif isinstance(data, LineList):
        data.line += by
        data.item_lines = [v + by for v in data.item_lines]
        for value in data:
            _shift(value, by)
