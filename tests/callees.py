"""Test helpers: a course file's function called in-process the way the sandbox calls it."""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from slamcourse.grading import testset
from slamcourse.grading.returns import to_plain
from slamcourse.sandbox import CallResult


def load(path: Path, name: str) -> Callable[..., Any]:
    """The function ``name`` of the Python file ``path`` (trusted course files only)."""
    namespace: dict[str, Any] = {}
    exec(compile(path.read_text(encoding="utf-8"), str(path), "exec"), namespace)
    fn: Callable[..., Any] = namespace[name]
    return fn


def in_process(fn: Callable[..., Any]) -> Callable[[Sequence[Sequence[Any]]], list[CallResult]]:
    """A stand-in for ``Worker.call_many``: each call on its own copy of the input, the result
    as plain data, an argument changed in place reported (``CallResult.mutated``)."""

    def call_many(calls: Sequence[Sequence[Any]]) -> list[CallResult]:
        results = []
        for args in calls:
            given = copy.deepcopy(list(args))
            before = [testset.input_key({"x": a}) for a in given]
            try:
                result = CallResult("ok", to_plain(fn(*given)))
            except Exception as exc:
                result = CallResult("raised", error=f"{type(exc).__name__}: {exc}")
            after = [testset.input_key({"x": a}) for a in given]
            changed = tuple(i for i, (b, a) in enumerate(zip(before, after, strict=True)) if a != b)
            results.append(dataclasses.replace(result, mutated=changed))
        return results

    return call_many
