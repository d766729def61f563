"""YAML loading that remembers line numbers, so every problem can be reported as ``path:line``.

Mappings load as :class:`LineDict` (a ``dict`` that knows the line of each key) and sequences as
:class:`LineList`. Duplicate keys, which PyYAML would silently overwrite, are reported.
"""

from __future__ import annotations

import json
import os
import zlib
from functools import lru_cache
from pathlib import Path
from typing import Any

from slamcourse.errors import CourseError, Problem


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


@lru_cache(maxsize=1)
def _loader_class() -> Any:
    """PyYAML's loader with our constructors; built (and PyYAML imported) on first parse."""
    import yaml

    base = getattr(yaml, "CSafeLoader", yaml.SafeLoader)  # the C parser where libyaml exists

    class Loader(base):  # type: ignore[misc, valid-type]
        def __init__(self, stream: str, path: str) -> None:
            super().__init__(stream)
            self.path = path
            self.problems: list[Problem] = []

    def construct_map(loader: Any, node: Any) -> LineDict:
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

    def construct_seq(loader: Any, node: Any) -> LineList:
        data = LineList(loader.construct_object(child, deep=True) for child in node.value)
        data.line = node.start_mark.line + 1
        data.item_lines = [child.start_mark.line + 1 for child in node.value]
        return data

    Loader.add_constructor("tag:yaml.org,2002:map", construct_map)
    Loader.add_constructor("tag:yaml.org,2002:seq", construct_seq)
    return Loader


def load_yaml(text: str, path: str | Path, *, first_line: int = 1) -> Any:
    """Parse ``text`` (from ``path``); raise :class:`CourseError` for syntax errors or duplicates.

    ``first_line`` shifts reported lines when ``text`` is a fragment (e.g. front matter).
    A parse is cached by content (see :func:`_cached`), so PyYAML is imported only for files
    that changed since they were last read.
    """
    data = _cached(text)
    if data is _MISSING:
        try:
            data = _parse(text, str(path))
        except CourseError as exc:
            if first_line == 1:
                raise
            by = first_line - 1
            raise CourseError(
                [
                    Problem(p.path, p.line + by if p.line else p.line, p.message)
                    for p in exc.problems
                ]
            ) from None
        _store(text, data)
    if first_line != 1:
        _shift(data, first_line - 1)
    return data


def _parse(text: str, path: str) -> Any:
    import yaml

    loader = _loader_class()(text, path)
    try:
        data = loader.get_single_data()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        if "nesting depth" in str(exc.problem):  # PyYAML ≥ 6.0.3 caps nesting itself
            raise CourseError(
                Problem(
                    path,
                    mark.line + 1 if mark else None,
                    "YAML nested too deeply to read; flatten the structure",
                )
            ) from None
        raise CourseError(
            Problem(
                path,
                mark.line + 1 if mark else None,
                f"YAML syntax error: {exc.problem or exc.context}; check indentation and "
                "quote strings that contain ': ' or start with a symbol",
            )
        ) from None
    except yaml.reader.ReaderError as exc:  # a character YAML forbids (e.g. a control code)
        line = text.count("\n", 0, exc.position) + 1 if isinstance(exc.position, int) else None
        char = f"U+{exc.character:04X}" if isinstance(exc.character, int) else "a character"
        raise CourseError(
            Problem(path, line, f"{char} is not allowed in YAML ({exc.reason}); remove it")
        ) from None
    except yaml.YAMLError as exc:
        raise CourseError(Problem(path, None, f"YAML error: {exc}")) from None
    except RecursionError:
        raise CourseError(
            Problem(path, None, "YAML nested too deeply to read; flatten the structure")
        ) from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise CourseError(Problem(path, None, f"unreadable YAML value: {exc}")) from None
    finally:
        loader.dispose()
    if loader.problems:
        raise CourseError(loader.problems)
    return data


# ---------------------------------------------------------------- the parse cache
# Parsed files are kept as JSON in <home>/cache/yaml/, named by a checksum of the text and
# holding the text itself, so an entry is used only for exactly the same text (like .pyc files,
# but keyed by content). Files that did not parse are never cached.

_MISSING = object()


def _cache_file(text: str) -> Path | None:
    """Where the parse of ``text`` is cached; None when no engine set a cache folder."""
    from slamcourse.settings import cache_dir

    root = cache_dir()
    if root is None:
        return None
    data = text.encode("utf-8", "surrogatepass")
    name = f"{zlib.crc32(data):08x}{zlib.adler32(data):08x}{len(data):x}.json"
    return root / "yaml" / name


def _cached(text: str) -> Any:
    from slamcourse.cache import touch

    path = _cache_file(text)
    if path is None:
        return _MISSING
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
        if entry["text"] != text:
            return _MISSING
        data = _decode(entry["data"])
    except (OSError, ValueError, KeyError, TypeError):
        return _MISSING
    touch(path)  # its last use, for the cache's eviction (slamcourse.cache)
    return data


def _store(text: str, data: Any) -> None:
    try:
        payload = json.dumps({"text": text, "data": _encode(data)})
    except (TypeError, ValueError):  # e.g. a YAML date: simply not cached
        return
    from slamcourse.cache import evict_if_due

    evict_if_due()
    path = _cache_file(text)
    if path is None:
        return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_name(f".{path.name}.{os.getpid()}")
        tmp.write_text(payload, encoding="utf-8")
        os.replace(tmp, path)
    except OSError:
        return


def _encode(value: Any) -> Any:
    if isinstance(value, LineDict):
        return {
            "d": [[k, _encode(v)] for k, v in value.items()],
            "l": value.line,
            "kl": value.key_lines,
            "vl": value.value_lines,
            "b": sorted(value.block_keys),
        }
    if isinstance(value, LineList):
        return {"s": [_encode(v) for v in value], "l": value.line, "il": value.item_lines}
    if value is None or isinstance(value, bool | int | float | str):
        return value
    raise TypeError(type(value).__name__)


def _decode(value: Any) -> Any:
    if isinstance(value, dict):
        if "d" in value:
            out = LineDict((k, _decode(v)) for k, v in value["d"])
            out.line, out.key_lines = value["l"], value["kl"]
            out.value_lines, out.block_keys = value["vl"], set(value["b"])
            return out
        items = LineList(_decode(v) for v in value["s"])
        items.line, items.item_lines = value["l"], value["il"]
        return items
    return value


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
