"""Calling an exercise's reference code (trusted, instructor-written numpy/scipy functions)."""

from __future__ import annotations

import copy
import importlib.util
import inspect
import sys
import threading
import zlib
from collections import OrderedDict
from pathlib import Path
from types import ModuleType
from typing import Any

from slamcourse.course.model import ExerciseSpec
from slamcourse.errors import CourseError, Problem

ModuleKey = tuple[str, int, int]  # a reference.py's resolved path, mtime (ns) and size
ResultKey = tuple[ModuleKey, str, str]  # its module, the function, the arguments' repr

_modules: dict[ModuleKey, ModuleType] = {}  # (never dropped)
_module_keys: dict[int, ModuleKey] = {}  # id(module) -> its key (ids stay unique: never dropped)
_resolved: dict[Path, Path] = {}

RESULTS_KEPT = 4096
"""Reference results kept for scalar arguments (:func:`call`): a text exercise's answer is
computed to grade it and again to explain it, and a batch meets the same variants again."""
_results: OrderedDict[ResultKey, Any] = OrderedDict()
_results_lock = threading.Lock()
_SCALARS = frozenset({int, float, str, bool, type(None)})


def module_for(spec: ExerciseSpec) -> ModuleType:
    """Import the ``reference.py`` beside ``spec``'s file (again only when it has changed)."""
    path = _resolved.get(spec.reference_path)
    if path is None:
        path = _resolved.setdefault(spec.reference_path, spec.reference_path.resolve())
    try:
        stat = path.stat()
        key = (str(path), stat.st_mtime_ns, stat.st_size)
    except OSError:
        key = (str(path), 0, 0)
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
    _module_keys[id(module)] = key
    return module


def function(spec: ExerciseSpec, name: str, line: int) -> Any:
    """The function ``name`` of the reference module; a missing name is reported at ``line``."""
    return _function_in(module_for(spec), spec, name, line)


def _function_in(module: ModuleType, spec: ExerciseSpec, name: str, line: int) -> Any:
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
    """Call reference function ``name`` with ``kwargs``; its failure is a :class:`CourseError`.

    Reference code is deterministic, so a result for arguments that are all plain scalars (a
    variant's parameters) is kept (the last :data:`RESULTS_KEPT`, per loaded module: a changed
    ``reference.py`` is a new module) and a copy of it returned when the same call comes again;
    failures are not kept."""
    module = module_for(spec)
    fn = _function_in(module, spec, name, line)
    key = _result_key(module, name, kwargs)
    if key is not None:
        with _results_lock:
            if key in _results:
                _results.move_to_end(key)
                return copy.deepcopy(_results[key])
    try:
        value = fn(**kwargs)
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
    if key is not None:
        with _results_lock:
            _results[key] = copy.deepcopy(value)
            while len(_results) > RESULTS_KEPT:
                _results.popitem(last=False)
    return value


def _result_key(module: ModuleType, name: str, kwargs: dict[str, Any]) -> ResultKey | None:
    """The key of a call whose arguments are all plain scalars (their reprs are exact: a float's
    is the shortest that reads back to the same bits), else None: not kept. The module is the
    loaded ``reference.py``, named by its file's path, mtime and size: the same in every
    process that reads the same file (:func:`kept_results` hands results between them)."""
    if any(type(v) not in _SCALARS for v in kwargs.values()):
        return None
    return (_module_keys[id(module)], name, repr(sorted(kwargs.items())))


def kept_results(
    spec: ExerciseSpec, calls: list[tuple[str, int, dict[str, Any]]]
) -> dict[ResultKey, Any]:
    """Make the ``calls`` (function name, line, arguments) of ``spec``'s reference and return
    their results as kept (keyed so that :func:`adopt_results` in another process, reading the
    same ``reference.py``, finds them): a batch computes the answers that are the same for
    every learner once, not once per grading process. Failures are left out (the grading
    process that needs the call reports them); so are calls that are never kept."""
    out: dict[ResultKey, Any] = {}
    for name, line, kwargs in calls:
        try:
            value = call(spec, name, line, kwargs)
        except CourseError:
            continue
        key = _result_key(module_for(spec), name, kwargs)
        if key is not None:
            out[key] = value
    return out


def adopt_results(results: dict[ResultKey, Any]) -> None:
    """Keep results another process computed (:func:`kept_results`) as if computed here."""
    with _results_lock:
        for key, value in results.items():
            _results[key] = value
            _results.move_to_end(key)
        while len(_results) > RESULTS_KEPT:
            _results.popitem(last=False)


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
