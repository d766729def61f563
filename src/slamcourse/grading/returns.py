"""Return-value specifications of code exercises, and comparison against the reference.

A spec is one of ``number``, ``integer``, ``angle``, ``boolean``, ``array`` or a list of these
(a fixed-length tuple, e.g. ``[number, angle]``). Tuples, lists and numpy arrays are accepted
alike: values arrive from the sandbox as plain JSON data (lists), and are checked here, in the
trusted parent, before any comparison.
"""

from __future__ import annotations

import copy
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from slamcourse.answers import format_number, wrap_angle
from slamcourse.course.model import Tolerance

SCALARS = ("number", "integer", "angle", "boolean")
TYPES = (*SCALARS, "array")


@dataclass(frozen=True)
class Mismatch:
    """Why a returned value is not accepted (shown to the learner)."""

    message: str


def parse_returns(raw: Any) -> tuple[str, ...] | str | None:
    """The spec from YAML, or ``None`` if it is malformed."""
    if isinstance(raw, str) and raw in TYPES:
        return raw
    if isinstance(raw, list) and raw and all(isinstance(r, str) and r in SCALARS for r in raw):
        return tuple(raw)
    return None


def describe(spec: tuple[str, ...] | str) -> str:
    if isinstance(spec, str):
        return {
            "number": "a number",
            "integer": "a whole number",
            "angle": "an angle in radians",
            "boolean": "True or False",
            "array": "an array",
        }[spec]
    return f"a tuple of {len(spec)} ({', '.join(spec)})"


def show(value: Any, limit: int = 200) -> str:
    """A value as the learner should read it in feedback (numbers compact, long output cut)."""
    if isinstance(value, bool) or value is None:
        text = repr(value)
    elif isinstance(value, int | float):
        text = format_number(float(value)) if isinstance(value, float) else str(value)
    elif isinstance(value, list | tuple):
        text = "[" + ", ".join(show(v, limit) for v in value) + "]"
    else:
        text = str(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _numbers(value: Any) -> list[float] | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return [float(value)]
    if isinstance(value, list | tuple):
        out: list[float] = []
        for v in value:
            inner = _numbers(v)
            if inner is None:
                return None
            out += inner
        return out
    return None


def _digits(value: Any, digits: int) -> str:
    if isinstance(value, bool) or value is None:
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value) if digits >= 17 else f"{value:.{digits}g}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_digits(v, digits) for v in value) + "]"
    return str(value)


def show_exact(value: Any, limit: int = 200) -> str:
    """A test input as the learner must type it to reproduce the call: floats with every digit
    (``3.141592653589793`` and the float next to it differ), ints as ints, tuples as tuples."""
    if isinstance(value, tuple):
        inner = ", ".join(show_exact(v, limit) for v in value)
        text = f"({inner}{',' if len(value) == 1 else ''})"
    elif isinstance(value, list):
        text = "[" + ", ".join(show_exact(v, limit) for v in value) + "]"
    elif hasattr(value, "tolist") and hasattr(value, "dtype"):
        text = f"np.array({show_exact(value.tolist(), limit)})"
    elif isinstance(value, str):
        text = repr(value)
    else:
        text = _digits(value, 17)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def show_pair(want: Any, got: Any, limit: int = 200) -> tuple[str, str]:
    """``want`` and ``got`` as :func:`show` prints them, but with as many digits as it takes
    for two different values to print differently ("expected -0.006984, got -0.006984" says
    nothing): 6, 9, 12, then all 17 significant digits."""
    a, b = show(want, limit), show(got, limit)
    if a != b or _numbers(want) is None or _numbers(got) is None or want == got:
        return a, b
    for digits in (6, 9, 12, 17):
        a, b = _digits(want, digits), _digits(got, digits)
        if a != b:
            break
    return _cut(a, limit), _cut(b, limit)


def _cut(text: str, limit: int) -> str:
    return text if len(text) <= limit else text[: limit - 1] + "…"


def to_plain(value: Any) -> Any:
    """Reference values (numpy, tuples) as the same plain data the sandbox returns."""
    tolist = getattr(value, "tolist", None)
    if callable(tolist):
        value = tolist()
    if isinstance(value, tuple | list):
        return [to_plain(v) for v in value]
    return value


Judge = Callable[[Any, Any, dict[str, Any]], str | None]
"""A code exercise's ``judge:`` (a reference.py function): ``judge(got, expected, kwargs)``
decides whether the learner's value ``got`` (plain data, already of the declared form) is right
for the input ``kwargs``, given the reference's value ``expected``; it returns ``None`` to
accept, else why not (shown to the learner). A judge grades stochastic code by a statistical
test, so it must be deterministic: the same value, the same verdict."""

_ANY_VALUE = Tolerance(rtol=0.0, atol=math.inf)  # any finite number matches (the form only)


def compare(
    spec: tuple[str, ...] | str,
    got: Any,
    want: Any,
    tol: Tolerance,
    *,
    plain: bool = False,
    judge: Judge | None = None,
    kwargs: dict[str, Any] | None = None,
    want_array: Any = None,
    got_array: Any = None,
) -> Mismatch | None:
    """``None`` when ``got`` (plain data from the learner) matches ``want`` (the reference);
    ``plain``: ``want`` is plain data already (a test set's expected values are). With a
    ``judge``, ``got`` must only have ``spec``'s form (the reference's shape, finite numbers);
    the judge, called with the input ``kwargs``, then decides instead of the tolerance.
    ``want_array``: ``numeric_array(want)``, when the caller keeps it (a test set's case
    converts its expected value once per batch, not once per learner). ``got_array``:
    ``numeric_array(got)``, where ``got`` came as a float array (``CallResult.array``)."""
    if not plain:
        want = to_plain(want)
    if judge is not None:
        return _judged(spec, got, want, judge, kwargs or {}, want_array, got_array)
    if isinstance(spec, tuple):
        if not isinstance(got, list):
            return Mismatch(f"expected {describe(spec)}, got {_what(got)}")
        if len(got) != len(spec):
            return Mismatch(f"expected {len(spec)} values, got {len(got)}")
        for i, (kind, g, w) in enumerate(zip(spec, got, want, strict=True)):
            problem = _scalar(kind, g, w, tol)
            if problem:
                return Mismatch(f"value {i + 1} of the tuple: {problem}")
        return None
    if spec == "array":
        return _array(got, want, tol, want_array, got_array)
    problem = _scalar(spec, got, want, tol)
    return Mismatch(problem) if problem else None


def _judged(
    spec: tuple[str, ...] | str,
    got: Any,
    want: Any,
    judge: Judge,
    kwargs: dict[str, Any],
    want_array: Any = None,
    got_array: Any = None,
) -> Mismatch | None:
    from slamcourse.errors import GraderError

    if spec == "array":
        form = _array(got, want, _ANY_VALUE, want_array, got_array)
    elif isinstance(spec, tuple):
        if not isinstance(got, list) or len(got) != len(spec):
            form = compare(spec, got, want, _ANY_VALUE)
        else:
            form = None
            for i, (kind, g, w) in enumerate(zip(spec, got, want, strict=True)):
                problem = _loose(kind, g, w)
                if problem:
                    form = Mismatch(f"value {i + 1} of the tuple: {problem}")
                    break
    else:
        problem = _loose(spec, got, want)
        form = Mismatch(problem) if problem else None
    if form is not None:
        return form
    # the judge gets copies: it cannot change the input or the value the feedback shows (a
    # rectangular array of numbers, checked above, is copied at numpy's speed)
    if spec == "array":  # (a float array's lists made again: the same floats, fresh)
        mine = got_array.tolist() if got_array is not None else _copy_array(got)
    else:
        mine = copy.deepcopy(got)
    try:
        verdict = judge(mine, want, copy.deepcopy(kwargs))
    except Exception as exc:
        raise GraderError(
            f"the exercise's judge failed on a value of the declared form: "
            f"{type(exc).__name__}: {exc}"
        ) from exc
    return None if verdict is None else Mismatch(str(verdict))


def _copy_array(got: Any) -> Any:
    """A copy of a value the judge may read: a list of numbers or a list of rows of numbers is
    copied row by row (numbers cannot change), anything else deeply."""
    if not isinstance(got, list):
        return got
    numbers = {int, float}
    kinds = set(map(type, got))
    if kinds <= numbers:
        return got[:]
    if kinds == {list} and set(map(type, itertools.chain.from_iterable(got))) <= numbers:
        return [row[:] for row in got]
    return copy.deepcopy(got)


def _loose(kind: str, got: Any, want: Any) -> str | None:
    """Whether a scalar has ``kind``'s form, whatever its value."""
    if kind == "boolean":
        return None if isinstance(got, bool) else f"expected True or False, got {_what(got)}"
    return _scalar("angle" if kind == "angle" else "number", got, want, _ANY_VALUE)


def _what(value: Any) -> str:
    if isinstance(value, list):
        return f"a sequence of {len(value)}"
    if isinstance(value, bool):
        return f"the boolean {value}"
    if value is None:
        return "None (did you forget to return?)"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, int | float):
        return f"the number {show(value)}"
    return str(value)  # an Unsupported marker explains itself


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    try:
        return float(value)
    except OverflowError:  # a whole number beyond the floats (said as such by _scalar)
        return math.inf


def _scalar(kind: str, got: Any, want: Any, tol: Tolerance) -> str | None:
    if kind == "boolean":
        if not isinstance(got, bool):
            return f"expected True or False, got {_what(got)}"
        return None if got == bool(want) else f"expected {bool(want)}, got {got}"
    number = _number(got)
    if number is None:
        return f"expected {describe(kind)}, got {_what(got)}"
    if not math.isfinite(number):
        if isinstance(got, int):
            return f"got a whole number of {got.bit_length()} bits, too large for a float"
        return f"got {show(number)}, which is not a finite number"
    target = float(want)
    if kind == "integer":
        if number != round(number):
            return f"expected a whole number, got {show(number)}"
        return (
            None if round(number) == round(target) else f"expected {int(target)}, got {show(got)}"
        )
    if kind == "angle":
        diff = abs(wrap_angle(number - target))
        ok = diff <= tol.atol + tol.rtol * abs(wrap_angle(target))
        if ok:
            return None
        want_text, got_text = show_pair(target, number)
        return f"expected {want_text} (mod 2π), got {got_text}"
    ok = abs(number - target) <= tol.atol + tol.rtol * abs(target)
    if ok:
        return None
    want_text, got_text = show_pair(target, number)
    return f"expected {want_text}, got {got_text}"


def _shape(value: Any) -> tuple[int, ...] | None:
    if not isinstance(value, list):
        return ()
    shapes = {_shape(v) for v in value}
    if len(shapes) > 1 or None in shapes:
        return None  # ragged
    inner = shapes.pop() if shapes else ()
    return (len(value), *inner) if inner is not None else None


def numeric_array(value: Any) -> Any:
    """``value`` (plain data) as a float ndarray when it is a rectangular list of numbers (no
    booleans: every entry's type is looked at, level by level), else None: the form
    :func:`_close_arrays` compares at numpy's speed."""
    import numpy as np

    if not isinstance(value, list):
        return None
    level: list[Any] = value
    while True:
        kinds = set(map(type, level))
        if kinds == {list}:
            level = list(itertools.chain.from_iterable(level))
            continue
        if not kinds <= {int, float}:  # booleans, ragged depths, anything else
            return None
        break
    try:
        return np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError):  # ragged rows, an int beyond the floats
        return None


_SMALL = 16  # a 1-D value this short is compared in Python: numpy's call overhead dominates


def _close_arrays(
    got: Any, want: Any, tol: Tolerance, want_array: Any = None, got_array: Any = None
) -> bool:
    """The common case at numpy speed: ``got`` is a rectangular array of finite numbers (no
    booleans) of ``want``'s shape within the tolerance. False means "look closely" (the walk
    below finds the entry and says what is wrong), not necessarily a mismatch.
    ``want_array``: ``numeric_array(want)`` if the caller has it; ``got_array`` likewise."""
    if not isinstance(got, list) or not isinstance(want, list):
        return False
    if len(got) == len(want) <= _SMALL and {int, float}.issuperset(map(type, got)):
        try:  # a short vector: the same rule, entry by entry (ints compared as floats)
            return all(
                type(w) in (int, float)
                and math.isfinite(g)
                and math.isfinite(w)
                and abs(float(g) - float(w)) <= tol.atol + tol.rtol * abs(float(w))
                for g, w in zip(got, want, strict=True)
            )
        except OverflowError:  # an int beyond floats: look closely
            return False
    g = numeric_array(got) if got_array is None else got_array
    w = numeric_array(want) if want_array is None else want_array
    if g is None or w is None or g.shape != w.shape:  # look closely
        return False
    return bool(_within(g, w, "number", tol).all())


def _array(
    got: Any, want: Any, tol: Tolerance, want_array: Any = None, got_array: Any = None
) -> Mismatch | None:
    if _close_arrays(got, want, tol, want_array, got_array):
        return None
    want_shape, got_shape = _shape(want), _shape(got)
    if got_shape is None:
        return Mismatch("the returned array is ragged (rows of different lengths)")
    if got_shape != want_shape:
        words = "×".join(map(str, want_shape or ())) or "a scalar"
        return Mismatch(
            f"expected an array of shape {words}, got {'×'.join(map(str, got_shape)) or 'a scalar'}"
        )

    def walk(g: Any, w: Any, index: tuple[int, ...]) -> Mismatch | None:
        if isinstance(w, list):
            for i, (gi, wi) in enumerate(zip(g, w, strict=True)):
                found = walk(gi, wi, (*index, i))
                if found:
                    return found
            return None
        problem = _scalar("number", g, w, tol)
        where = "[" + "][".join(map(str, index)) + "]"
        return Mismatch(f"entry {where}: {problem}") if problem else None

    return walk(got, want, ())


def accepted(
    spec: tuple[str, ...] | str,
    values: list[Any],
    wants: list[Any],
    tol: Tolerance,
    want_arrays: list[Any] | None = None,
    got_arrays: list[Any] | None = None,
) -> list[bool]:
    """For many learner values at once (plain data, each with its reference value in
    ``wants``): True where :func:`compare` certainly returns ``None`` (no judge), decided at
    numpy's speed over the whole group. False means "not shown here": the value is compared
    one by one, which gives the verdict and its message (a group whose values do not all have
    one form, e.g. a ragged or boolean entry, is left to that, whole). ``want_arrays``: the
    wants' :func:`numeric_array`, where the caller keeps them (``array`` only); ``got_arrays``:
    each value's, where it came as a float array (else None).

    Every test here implies the one-by-one rule's acceptance, with the same floating-point
    operations: ``|g − w| ≤ atol + rtol·|w|`` on float64, an angle's difference taken as is only
    when it is already inside (−π, π) and its reference inside [−π, π] (where wrapping changes
    neither)."""
    import numpy as np

    n = len(values)
    none = [False] * n
    if not n or len(wants) != n:
        return none
    try:
        if spec == "array":
            if want_arrays is None:
                want_arrays = [numeric_array(w) for w in wants]
            if set(map(type, values)) != {list} or any(w is None for w in want_arrays):
                return none  # (each value a list, not a scalar; each reference an array)
            alike: dict[tuple[int, ...], list[int]] = {}  # stacked by the reference's shape
            for i, w in enumerate(want_arrays):
                alike.setdefault(w.shape, []).append(i)
            out = none[:]
            for shape, where in alike.items():
                if got_arrays is not None and all(got_arrays[i] is not None for i in where):
                    arrays = [got_arrays[i] for i in where]
                    if any(a.shape != shape for a in arrays):
                        continue
                    got = np.stack(arrays)
                else:
                    got = numeric_array([values[i] for i in where])
                if got is None or got.shape != (len(where), *shape):
                    continue
                want = np.stack([want_arrays[i] for i in where])
                ok = _within(got, want, "number", tol).reshape(len(where), -1).all(axis=1)
                for i, yes in zip(where, ok.tolist(), strict=True):
                    out[i] = yes
            return out
        if isinstance(spec, tuple):
            if "boolean" in spec or not all(
                type(v) is list and len(v) == len(spec) for v in values
            ):
                return none
            got, want = numeric_array(values), numeric_array(wants)
            if (
                got is None
                or want is None
                or got.shape != want.shape
                or want.shape != (n, len(spec))
            ):
                return none
            ok = np.ones(n, dtype=bool)
            for k, kind in enumerate(spec):
                ok &= _within(got[:, k], want[:, k], kind, tol)
            return ok.tolist()
        if spec == "boolean":
            return [type(g) is bool and g == bool(w) for g, w in zip(values, wants, strict=True)]
        if not {int, float}.issuperset(map(type, values)) or not {int, float}.issuperset(
            map(type, wants)
        ):
            return none
        cleared: list[bool] = _within(
            np.array(values, dtype=float), np.array(wants, dtype=float), spec, tol
        ).tolist()
        return cleared
    except (TypeError, ValueError, OverflowError):  # e.g. a whole number beyond the floats
        return none


def _within(got: Any, want: Any, kind: str, tol: Tolerance) -> Any:
    """Elementwise: ``got`` (float array) certainly accepted for ``want`` as a ``kind``."""
    import numpy as np

    finite = np.isfinite(got) & np.isfinite(want)
    with np.errstate(invalid="ignore", over="ignore"):
        if kind == "integer":
            whole = np.rint(got)
            return finite & (got == whole) & (whole == np.rint(want))
        diff = np.abs(got - want)
        ok = finite & (diff <= tol.atol + tol.rtol * np.abs(want))
        if kind == "angle":
            ok &= (diff < math.pi) & (np.abs(want) <= math.pi)
    return ok
