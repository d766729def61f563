"""Calling an exercise's reference code (trusted, instructor-written numpy/scipy functions)."""

from __future__ import annotations

import importlib.util
import inspect
import sys
import zlib
from pathlib import Path
from types import ModuleType
from typing import Any

from slamcourse.course.model import ExerciseSpec
from slamcourse.errors import CourseError, Problem

_modules: dict[tuple[Path, int, int], ModuleType] = {}


def module_for(spec: ExerciseSpec) -> ModuleType:
    """Import the ``reference.py`` beside ``spec``'s file (again only when it has changed)."""
    path = spec.reference_path.resolve()
    try:
        stat = path.stat()
        key = (path, stat.st_mtime_ns, stat.st_size)
    except OSError:
        key = (path, 0, 0)
    if key in _modules:
        return _modules[key]
    rel = _rel(spec, spec.reference_path)
    name = f"slamcourse_reference_{zlib.crc32(repr(key).encode()):08x}_{len(_modules)}"
    loader_spec = importlib.util.spec_from_file_location(name, path)
    if loader_spec is None or loader_spec.loader is None or not path.is_file():
        raise CourseError(Problem(rel, None, "reference module not found"))
    module = importlib.util.module_from_spec(loader_spec)
    sys.modules[name] = module
    try:
        loader_spec.loader.exec_module(module)
    except Exception as exc:
        sys.modules.pop(name, None)
        raise CourseError(
            Problem(
                rel,
                _error_line(exc, path),
                f"importing the reference module failed: {type(exc).__name__}: {exc}",
            )
        ) from None
    _modules[key] = module
    return module


def function(spec: ExerciseSpec, name: str, line: int) -> Any:
    """The function ``name`` of the reference module; a missing name is reported at ``line``."""
    module = module_for(spec)
    fn = getattr(module, name, None)
    if not callable(fn):
        public = [n for n, v in vars(module).items() if callable(v) and not n.startswith("_")]
        from slamcourse.course.schema import suggest

        raise CourseError(
            Problem(
                _rel(spec, spec.path),
                line,
                f"reference.py has no function '{name}'{suggest(name, public)}",
            )
        )
    return fn


def call(spec: ExerciseSpec, name: str, line: int, kwargs: dict[str, Any]) -> Any:
    """Call reference function ``name`` with ``kwargs``; its failure is a :class:`CourseError`."""
    fn = function(spec, name, line)
    try:
        return fn(**kwargs)
    except Exception as exc:
        path = spec.reference_path.resolve()
        where = _error_line(exc, path)
        if where is None:
            try:
                where = inspect.getsourcelines(fn)[1]
            except (OSError, TypeError):
                where = None
        args = ", ".join(f"{k}={v!r}" for k, v in kwargs.items())
        raise CourseError(
            Problem(
                _rel(spec, spec.reference_path),
                where,
                f"{name}({args}) raised {type(exc).__name__}: {exc}",
            )
        ) from None


def _error_line(exc: BaseException, path: Path) -> int | None:
    line = None
    import traceback  # only on errors

    for frame in traceback.extract_tb(exc.__traceback__):
        if Path(frame.filename).resolve() == path:
            line = frame.lineno
    if line is None and isinstance(exc, SyntaxError) and exc.lineno:
        line = exc.lineno
    return line


def _rel(spec: ExerciseSpec, path: Path) -> str:
    from slamcourse.errors import relpath

    return relpath(path, spec.course_root)
