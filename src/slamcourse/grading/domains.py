"""Argument types of code exercises, and the boundary inputs each type calls for.

A code exercise declares what each parameter of its function *is* (``types:`` in its YAML, one
entry per signature parameter). Every exercise using a type then gets the same classes of
**boundary inputs**, derived from its own explicit examples and drawn inputs: ±π and the floats
next to it, whole numbers given as Python ``int``, tuples and arrays where the prompt says
"sequence", the domain's extremes, g2o texts with CRLF line ends or no final newline, …
(:func:`boundary_inputs`). The test set (``grading/testset.py``) keeps a derived input only
where the exercise's reference is defined on it (it returns finite values without raising) and
the exercise's ``valid`` function, if it has one, accepts it; the validator proves that every
class the types call for (:func:`boundary_classes`) keeps at least one input.

Vocabulary (docs/authoring.md, "Argument types and boundary inputs"); a bare name
(``a: angle``) or a mapping with parameters (``n: {type: count, range: [1, 30000]}``):

=============  ==========================================  ===================================
type           what it is                                  parameters
=============  ==========================================  ===================================
real           a float                                     range, open
angle          radians (default range [-π, π])             range, open
count          a whole number                              range (required)
probability    a number in [0, 1]                          range, open
vector         a sequence of numbers                       range, length, angles, ordered,
                                                           ties, empty
pose           SE(2) pose (x, y, θ), θ an angle            range (of x and y)
poses          a sequence of poses                         range (of x and y), empty
points         a sequence of points (an N×2 array)         range, ordered, ties, empty
covariance     symmetric positive semidefinite matrix      size, range (of the diagonal)
information    symmetric positive semidefinite matrix      size, range (of the diagonal)
matrix         a general 2-D array                         size, range (of the entries)
rotation       a 3×3 rotation matrix (orthonormal, det +1)
pose3          a 3-D pose as a 4×4 homogeneous matrix      range (of the translation)
indices        a sequence of whole-number indices          ordered, ties, empty
edges          a sequence of tuples such as (i, j, d)      ordered, ties, empty
g2o            the text of a g2o file
edge3          the text of EDGE3 lines (a 3-D pose graph)
text           other text
choice         one of a few values (no boundaries)
data           anything else (no boundaries)
=============  ==========================================  ===================================

Extensions of the vocabulary first agreed (all optional): ``open: low | high | both`` (real,
angle, probability: which ends of the range are excluded), ``angles: [i, …]`` (vector: the
entries that are angles in radians; they get the angle classes and take part in headings
across ±π), ``ties: true`` (vector, points, indices, edges: every entry given twice is in the
domain), ``empty: true`` (vector, poses, points, indices, edges: the empty sequence is in the
domain), ``ordered: false`` (the order carries no meaning: reversed order is derived),
``size: [rows, cols]`` for a non-square ``matrix``, range ends written with π (``[-pi, pi]``,
``[0, 2*pi]``).

``rotation`` and ``pose3`` carry a domain check of their own (:func:`rotation_problem`,
:func:`pose3_problem`: orthonormal to :data:`ORTHONORMAL`, determinant positive, a pose's last
row ``[0, 0, 0, 1]`` and its translation inside the range): a derived matrix that fails it is
never emitted, a base that fails it is not transformed, and an example that fails it is
reported where the exercise loads (:func:`outside`).

Everything here is pure Python and deterministic; numpy is imported only when boundary inputs
are derived (arrays are among them), never when an exercise is loaded.
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from slamcourse.course.schema import Checker

PI = math.pi
DEFAULT_LIMIT = 300
"""Boundary inputs :func:`boundary_inputs` returns at most (first bases first)."""
SPREAD = 2
"""Inputs per boundary class, each in the exercise's domain (``admissible``), from the most
telling bases that give one: two, because a class can show nothing on one base (an edge line
moved first in a file with a single edge) and something on the next."""
LARGE_BASE = 4
"""A base more than this many times the median base's size (:func:`_size`) is used last."""

TYPES: dict[str, str] = {
    "real": "a float (optional range)",
    "angle": "an angle in radians (range [-pi, pi] unless declared)",
    "count": "a whole number (range required)",
    "probability": "a number in [0, 1] (optional range, open ends)",
    "vector": "a sequence of numbers (optional range of entries, length, angle entries)",
    "pose": "an SE(2) pose (x, y, theta): three numbers, theta an angle",
    "poses": "a sequence of poses",
    "points": "a sequence of 2-D points (an N x 2 array)",
    "covariance": "a symmetric positive semidefinite matrix",
    "information": "a symmetric positive semidefinite matrix (an information matrix)",
    "matrix": "a general 2-D array",
    "rotation": "a 3 x 3 rotation matrix (orthonormal to 1e-9, determinant +1)",
    "pose3": "a 3-D pose: a 4 x 4 homogeneous matrix [[R, t], [0, 0, 0, 1]]",
    "indices": "a sequence of whole-number indices",
    "edges": "a sequence of tuples or lists such as (i, j, d) or (i, j, z, info)",
    "g2o": "the text of a g2o file",
    "edge3": "the text of EDGE3 lines (a 3-D pose graph: i j x y z roll pitch yaw, 21 numbers)",
    "text": "other text",
    "choice": "one of a few values (no boundary inputs)",
    "data": "anything else (no boundary inputs)",
}
"""The type names, each with a one-line description."""

_PARAMETERS: dict[str, tuple[str, ...]] = {
    "real": ("range", "open"),
    "angle": ("range", "open"),
    "count": ("range",),
    "probability": ("range", "open"),
    "vector": ("range", "length", "angles", "ordered", "ties", "empty"),
    "pose": ("range",),
    "poses": ("range", "empty"),
    "points": ("range", "ordered", "ties", "empty"),
    "covariance": ("size", "range"),
    "information": ("size", "range"),
    "matrix": ("size", "range"),
    "rotation": (),
    "pose3": ("range",),
    "indices": ("ordered", "ties", "empty"),
    "edges": ("ordered", "ties", "empty"),
    "g2o": (),
    "edge3": (),
    "text": (),
    "choice": (),
    "data": (),
}
_OPEN = ("none", "low", "high", "both")
_SEQUENCES = ("vector", "pose", "poses", "points", "indices", "edges")
_MATRICES = ("covariance", "information", "matrix")
_SCALARS = ("real", "angle", "count", "probability")

SMALL = (1e-3, -1e-3, 7e-3, -7e-3)
"""Small nonzero values (an angle under 0.01 rad: where approximations and thresholds fail)."""
ACROSS = (0.05, 1e-3)
"""How far either side of ±π a pair of headings is set (their difference crosses ±π)."""
_WHOLE_ANGLES = (0, 1, -1, 3, -3, 4, -4, 6, -6)
_SCALE = 1e3
"""Factor of the large (and, inverted, the small) scale of a matrix without a range."""


@dataclass(frozen=True)
class ArgType:
    """The declared type of one parameter: ``type`` is a name of :data:`TYPES`; ``bounds`` the
    range (an angle's default ``(-π, π)``, a probability's ``(0, 1)``, else None when none
    is declared); ``open`` which ends of it are excluded; the rest as in the vocabulary."""

    name: str
    type: str
    bounds: tuple[float, float] | None = None
    open: str = "none"
    length: int | None = None
    size: tuple[int, int] | None = None
    angles: tuple[int, ...] = ()
    ordered: bool = True
    ties: bool = False
    empty: bool = False
    line: int = 0

    def contains(self, x: float) -> bool:
        """Whether the number ``x`` lies in the declared range (any finite number without)."""
        if not math.isfinite(x):
            return False
        if self.bounds is None:
            return True
        low, high = self.bounds
        low_ok = x > low if self.open in ("low", "both") else x >= low
        high_ok = x < high if self.open in ("high", "both") else x <= high
        return low_ok and high_ok


@dataclass(frozen=True)
class Derived:
    """A boundary input: ``kwargs`` (a new input dict; arguments the transform did not touch
    are the base's own objects: treat them as read-only) and ``label``, its class (e.g.
    ``angle ±π (a)``)."""

    kwargs: dict[str, Any]
    label: str


Make = Callable[[dict[str, Any]], "dict[str, Any] | None"]
Change = Callable[[Any], Any]  # an argument's new value, or None (not applicable to it)


@dataclass(frozen=True)
class _Transform:
    label: str
    make: Make
    pure: bool  # only the representation changes (list → tuple, CRLF, …), never a value
    near: tuple[str, float] | None = None  # (argument, value): bases nearest to it first


# ------------------------------------------------------------------------------ the classes


def boundary_classes(types: Iterable[ArgType]) -> set[str]:
    """The labels of the boundary classes ``types`` call for (each is what
    :func:`boundary_inputs` emits for it)."""
    return {t.label for t in _transforms(tuple(types))}


def boundary_inputs(
    types: Iterable[ArgType],
    bases: Sequence[dict[str, Any]],
    *,
    limit: int = DEFAULT_LIMIT,
    admissible: Callable[[dict[str, Any]], bool] | None = None,
    size: Callable[[dict[str, Any]], int] | None = None,
) -> list[Derived]:
    """The boundary inputs of ``types``, derived from ``bases`` (ordinary input dicts: the
    exercise's examples and drawn inputs).

    Each class's transform is applied to the first :data:`SPREAD` bases on which it applies
    and changes something, in order of preference: the least trivial first (the largest share
    of numbers that are nonzero and not whole), else in the order given; a value set to a
    range's end (``lowest value``, ``highest value``) starts from the bases nearest to it.
    Bases more than :data:`LARGE_BASE` times the median base's size come after all others; a
    change of form (a tuple, an array) of an empty argument is used only where no other base
    gives the class. ``size(base)``: how costly a base is (default :func:`input_size`; a test
    set adds the size of the reference's output, which a count such as ``n`` samples sets).
    ``admissible(kwargs)``: whether a derived input lies in the exercise's domain; one that
    does not is skipped and the next base tried (without it, every changed input counts). A
    transform
    that changes nothing on any base (they all have the property already, e.g. all are lists)
    yields the last bases given (drawn ones rather than examples) unchanged, a base not yet
    given for another class first, under the class's label. The other arguments keep the
    base's values. The first base of every transform comes first, so ``limit`` cuts the spare
    bases first. Deterministic; no randomness.
    """
    declared = tuple(types)
    transforms = _transforms(declared)
    names = {t.name for t in declared}
    distinct: list[tuple[int, dict[str, Any], Any]] = []  # (place given, base, its key)
    for base in bases:
        if not isinstance(base, dict) or not names <= set(base):
            continue
        key = _key(base)
        if all(key != k for _, _, k in distinct):
            distinct.append((len(distinct), base, key))
    # a boundary class is about values and types, not size: large bases (a real data set among
    # small synthetic ones) are used last, so that the class is reached at a small input's cost
    sizes = [(size or input_size)(base) for _, base, _ in distinct]
    large_above = LARGE_BASE * sorted(sizes)[len(sizes) // 2] if sizes else 0
    large = {b[0] for b, size in zip(distinct, sizes, strict=True) if size > large_above}
    ordered = sorted(distinct, key=lambda b: (b[0] in large, -_score(b[1])))  # stable: ties kept
    shown: set[int] = set()  # bases already given unchanged for a class
    rounds: list[list[Derived]] = [[] for _ in range(SPREAD)]
    for transform in transforms:
        found: list[dict[str, Any]] = []
        found_keys: list[Any] = []
        unchanged: list[tuple[int, dict[str, Any]]] = []
        candidates = ordered
        weak: list[tuple[Any, dict[str, Any]]] = []
        if transform.near is not None:  # e.g. the largest count from the largest bases
            name, target = transform.near
            candidates = sorted(
                ordered, key=lambda b: (b[0] in large, _distance(b[1][name], target))
            )
        for place, base, base_key in candidates:
            try:
                out = transform.make(base)
            except (ArithmeticError, ValueError, TypeError, IndexError, KeyError, AttributeError):
                out = None  # a base of another shape than the type says: not this one
            if out is None:
                continue
            key = _key(out)
            if key == base_key:
                unchanged.append((place, out))
            elif key not in found_keys:
                if transform.pure and _only_empty_changed(base, out):
                    weak.append((key, out))  # [] as an array shows nothing: a last resort
                    continue
                if admissible is not None and not admissible(out):
                    continue
                found.append(out)
                found_keys.append(key)
                if len(found) >= SPREAD:
                    break
        for key, out in weak:
            if len(found) >= SPREAD:
                break
            if admissible is None or admissible(out):
                found.append(out)
                found_keys.append(key)
        if not found:  # every base has the property already: the last bases given (drawn
            # ones, after the examples) show it, each base for one class only if it can
            latest = sorted(unchanged, key=lambda u: (u[0] in shown, -u[0]))[:SPREAD]
            shown.update(place for place, _ in latest)
            found = [out for _, out in latest]
        else:  # a base that has the property already reaches the class too (the test set
            # holds it anyway): e.g. an example with n = 1 when no other base allows n = 1
            found += [out for _, out in unchanged[:1]]
        for i, kwargs in enumerate(found):
            rounds[min(i, SPREAD - 1)].append(Derived(kwargs, transform.label))
    derived = [d for r in rounds for d in r]
    return derived[: max(0, limit)]


def representation_classes(types: Iterable[ArgType]) -> set[str]:
    """The labels among :func:`boundary_classes` whose inputs hold the same values as their
    base in another form (a tuple for a list, an array, CRLF line ends, exponent notation, an
    edge line moved first, …): a function right on the base must be right on them."""
    return {t.label for t in _transforms(tuple(types)) if t.pure}


def _transforms(types: tuple[ArgType, ...]) -> list[_Transform]:
    """Every class's transforms, argument by argument in order, then pairs of headings."""
    out: list[_Transform] = []
    for t in types:
        build = _BUILDERS.get(t.type)
        if build is not None:
            out += build(t)
    out += _pairs(types)
    return out


def _on(name: str, change: Change) -> Make:
    """A transform of the input that replaces argument ``name`` with ``change(value)``."""

    def make(kwargs: dict[str, Any]) -> dict[str, Any] | None:
        new = change(kwargs[name])
        if new is None:
            return None
        out = dict(kwargs)
        out[name] = new
        return out

    return make


def _one(label: str, name: str, change: Change, *, pure: bool = False) -> _Transform:
    return _Transform(f"{label} ({name})", _on(name, change), pure)


def _const(value: Any) -> Change:
    return lambda _old: value


def _set(label: str, name: str, value: float) -> _Transform:
    """Argument ``name`` set to ``value``, starting from the bases whose value is nearest."""
    return _Transform(f"{label} ({name})", _on(name, _const(value)), False, (name, value))


def _distance(value: Any, target: float) -> float:
    number = _number(value)
    return abs(number - target) if number is not None else math.inf


# ---- scalars


def _real(t: ArgType) -> list[_Transform]:
    out = _ends(t)
    if _int_range(t) is not None:
        out.append(_one("whole numbers as int", t.name, lambda x: _round_scalar(x, t)))
    out += [_one("small nonzero", t.name, _const(v)) for v in SMALL if t.contains(v)]
    return out


def _angle(t: ArgType) -> list[_Transform]:
    out = []
    for label, values in _angle_values(t):
        out += [_one(label, t.name, _const(v)) for v in values]
    whole = [v for v in _WHOLE_ANGLES if t.contains(v)]
    span = _int_range(t)
    if not whole and span is not None:
        whole = [int(span[0])]
    out += [_one("whole numbers as int", t.name, _const(v)) for v in whole]
    if t.bounds is not None and (t.bounds != (-PI, PI) or t.open != "none"):
        out += _ends(t)
    return out


def _count(t: ArgType) -> list[_Transform]:
    if t.bounds is None:
        return []
    low, high = t.bounds
    return [
        _set("lowest value", t.name, math.ceil(low)),
        _set("highest value", t.name, math.floor(high)),
    ]


def _probability(t: ArgType) -> list[_Transform]:
    out = _ends(t)
    if t.contains(0.5):
        out.append(_one("probability ½", t.name, _const(0.5)))
    out += [_one("whole numbers as int", t.name, _const(v)) for v in (0, 1) if t.contains(v)]
    return out


def _ends(t: ArgType) -> list[_Transform]:
    """The range's two ends (inside it: an open end is approached to a millionth of the
    range)."""
    if t.bounds is None:
        return []
    low, high = t.bounds
    step = (high - low) * 1e-6
    lo = low + step if t.open in ("low", "both") else float(low)
    hi = high - step if t.open in ("high", "both") else float(high)
    return [_set("lowest value", t.name, lo), _set("highest value", t.name, hi)]


def _angle_values(t: ArgType) -> list[tuple[str, list[float]]]:
    """The angle classes and their values inside ``t``'s range."""
    # past ±π, but never at an odd multiple of π other than ±π itself: there the float
    # nearest 3π lies a rounding error either side of the wrap, and correct methods differ
    beyond = (PI + 1e-3, -PI - 1e-3, 2 * PI, -2 * PI, 3 * PI + 0.5, -3 * PI - 0.5)
    candidates: list[tuple[str, tuple[float, ...]]] = [
        ("angle 0", (0.0,)),
        ("angle ±π", (PI, -PI)),
        ("angle next to ±π", (math.nextafter(PI, 0.0), math.nextafter(-PI, 0.0))),
        ("angle ±π/2", (PI / 2, -PI / 2)),
        ("small angle", SMALL),
        ("angle past ±π", beyond),
    ]
    ends = t.bounds or ()  # a range's ends are classes of their own (the same inputs once)
    found = []
    for label, values in candidates:
        inside = [v for v in values if t.contains(v) and not (label in _PAST and v in ends)]
        if inside:
            found.append((label, inside))
    return found


_PAST = ("angle past ±π",)


_HEADING = ArgType("θ", "angle", (-PI, PI))


def _int_range(t: ArgType) -> tuple[float, float] | None:
    """The whole numbers allowed by ``t``'s range as (lowest, highest); None if there is none;
    infinite ends without a range."""
    if t.bounds is None:
        return (-math.inf, math.inf)
    low, high = t.bounds
    lo, hi = math.ceil(low), math.floor(high)
    if not t.contains(lo):
        lo += 1
    if not t.contains(hi):
        hi -= 1
    return (lo, hi) if lo <= hi else None


def _round_to(x: float, t: ArgType) -> int | None:
    span = _int_range(t)
    if span is None or not math.isfinite(x):
        return None
    r = math.floor(x + 0.5)
    return int(min(max(r, span[0]), span[1]))


def _round_scalar(x: Any, t: ArgType) -> int | None:
    n = _number(x)
    return None if n is None else _round_to(n, t)


# ---- sequences of numbers


def _vector(t: ArgType) -> list[_Transform]:
    n = t.name
    out = _flat_forms(t, "float64")
    out.append(_one("whole numbers as int", n, lambda v: _flat_round(v, t, angles=t.angles)))
    out.append(_one("int64 ndarray", n, lambda v: _flat_round(v, t, angles=t.angles, array=True)))
    if t.bounds is not None:
        out.append(_one("entries at range ends", n, lambda v: _flat_ends(v, t)))
    for i in t.angles:
        for label, values in _angle_values(_HEADING):
            out += [
                _Transform(f"{label} ({n}[{i}])", _on(n, _set_entry(i, v)), False) for v in values
            ]
    out += _order_classes(t)
    return out


def _pose(t: ArgType) -> list[_Transform]:
    n = t.name
    out = _flat_forms(t, "float64")
    out.append(_one("whole numbers as int", n, lambda v: _flat_round(v, t, angles=(2,))))
    out.append(_one("int64 ndarray", n, lambda v: _flat_round(v, t, angles=(2,), array=True)))
    for label, values in _angle_values(_HEADING):
        out += [_one(label, n, _set_entry(2, v, length=3)) for v in values]
    if t.bounds is not None:
        for upper in (True, False):
            out.append(_one("positions at range ends", n, _pose_corner(t, upper)))
    return out


def _indices(t: ArgType) -> list[_Transform]:
    return _flat_forms(t, "int64") + _order_classes(t)


def _flat_forms(t: ArgType, dtype: str) -> list[_Transform]:
    n = t.name
    return [
        _one("list", n, lambda v: _flat_as(v, t, "list"), pure=True),
        _one("tuple", n, lambda v: _flat_as(v, t, "tuple"), pure=True),
        _one("ndarray", n, lambda v: _flat_as(v, t, dtype), pure=True),
    ]


def _order_classes(t: ArgType) -> list[_Transform]:
    out = []
    if not t.ordered:
        out.append(_one("reversed order", t.name, _reversed))
    if t.ties:
        out.append(_one("exact ties", t.name, _twice))
    if t.empty:
        out.append(_one("empty", t.name, _emptied))
    return out


def _flat(v: Any, t: ArgType | None = None) -> list[int | float] | None:
    """The numbers of a flat sequence (list, tuple or 1-D array), or None."""
    if _is_array(v):
        if v.ndim != 1:
            return None
        items = v.tolist()
    elif isinstance(v, list | tuple):
        items = list(v)
    else:
        return None
    numbers = [_number(x) for x in items]
    if any(x is None for x in numbers):
        return None
    flat = [x for x in numbers if x is not None]
    if t is not None:
        want = 3 if t.type == "pose" else t.length
        if want is not None and len(flat) != want:
            return None
    return flat


def _flat_as(v: Any, t: ArgType, form: str) -> Any:
    values = _flat(v, t)
    if values is None:
        return None
    if form == "list":
        return list(values)
    if form == "tuple":
        return tuple(values)
    return _np().array(values, dtype=form)


def _like(values: list[Any], base: Any) -> Any:
    """``values`` in the container of ``base`` (a tuple stays a tuple; else a list)."""
    return tuple(values) if isinstance(base, tuple) else list(values)


def _flat_round(v: Any, t: ArgType, *, angles: Iterable[int], array: bool = False) -> Any:
    values = _flat(v, t)
    if values is None:
        return None
    angle_set = set(angles)
    rounded = []
    for i, x in enumerate(values):
        r = _round_to(x, _HEADING if i in angle_set else t)
        if r is None:
            return None
        rounded.append(r)
    if array:
        return _np().array(rounded, dtype="int64")
    return _like(rounded, v)


def _flat_ends(v: Any, t: ArgType) -> Any:
    values = _flat(v, t)
    if values is None or t.bounds is None:
        return None
    low, high = t.bounds
    step = (high - low) * 1e-6
    lo = low + step if t.open in ("low", "both") else float(low)
    hi = high - step if t.open in ("high", "both") else float(high)
    middle = (low + high) / 2
    out = [x if i in t.angles else (hi if x >= middle else lo) for i, x in enumerate(values)]
    if _is_array(v):
        return _np().array(out, dtype="float64")
    return _like(out, v)


def _set_entry(index: int, value: float, length: int | None = None) -> Change:
    """Entry ``index`` of a flat sequence set to ``value`` (the container kept; an array
    becomes a float array)."""

    def change(v: Any) -> Any:
        values = _flat(v)
        if values is None or index >= len(values) or (length and len(values) != length):
            return None
        values = list(values)
        values[index] = value
        if _is_array(v):
            return _np().array(values, dtype="float64")
        return _like(values, v)

    return change


def _pose_corner(t: ArgType, upper: bool) -> Change:
    def change(v: Any) -> Any:
        values = _flat(v, t)
        if values is None or t.bounds is None:
            return None
        end = float(t.bounds[1] if upper else t.bounds[0])
        out = [end, end, values[2]]
        if _is_array(v):
            return _np().array(out, dtype="float64")
        return _like(out, v)

    return change


def _reversed(v: Any) -> Any:
    if _is_array(v):
        return v[::-1].copy()
    if isinstance(v, list | tuple):
        return _like(list(v)[::-1], v)
    return None


def _twice(v: Any) -> Any:
    if _is_array(v):
        return _np().concatenate([v, v])
    if isinstance(v, list | tuple) and len(v) > 0:
        return _like([*v, *v], v)
    return None


def _emptied(v: Any) -> Any:
    if isinstance(v, tuple):
        return ()
    if isinstance(v, list) or _is_array(v):
        return []
    return None


# ---- sequences of rows: poses, points, edges


def _rows(v: Any, width: int | None = None) -> list[list[int | float]] | None:
    """The rows of numbers of a sequence of flat sequences (or a 2-D array), or None."""
    if _is_array(v):
        if v.ndim != 2:
            return None
        items = list(v)
    elif isinstance(v, list | tuple):
        items = list(v)
    else:
        return None
    rows = []
    for item in items:
        row = _flat(item)
        if row is None or (width is not None and len(row) != width):
            return None
        rows.append(row)
    if rows and len({len(r) for r in rows}) != 1:
        return None
    return rows


def _row_form(outer: str, inner: str) -> Callable[[list[list[Any]]], Any]:
    def form(rows: list[list[Any]]) -> Any:
        if outer == "ndarray":
            return _np().array(rows, dtype=inner)
        made = [tuple(r) if inner == "tuple" else list(r) for r in rows]
        return tuple(made) if outer == "tuple" else made

    return form


_ROW_FORMS = (
    ("list of lists", "list", "list"),
    ("list of tuples", "list", "tuple"),
    ("tuple of lists", "tuple", "list"),
)


def _rows_like(rows: list[list[Any]], base: Any) -> Any:
    """``rows`` in the containers of ``base`` (tuples stay tuples; an array becomes lists)."""
    inner = "list"
    if isinstance(base, list | tuple) and base and isinstance(base[0], tuple):
        inner = "tuple"
    return _row_form("tuple" if isinstance(base, tuple) else "list", inner)(rows)


def _rows_out(rows: list[list[Any]], base: Any) -> Any:
    """Changed values in ``base``'s form (an array stays a float array)."""
    if _is_array(base):
        return _np().array(rows, dtype="float64")
    return _rows_like(rows, base)


def _poses(t: ArgType) -> list[_Transform]:
    out = _row_classes(t, 3, angles=(2,))
    for label, values in _angle_values(_HEADING):
        out += [_one(label, t.name, _rotated_to(t, v)) for v in values]
    out.append(_one("headings across ±π", t.name, _across(t)))
    if t.bounds is not None:
        out += [_one("positions at range ends", t.name, _corner(t, up, 3)) for up in (1, 0)]
    if t.empty:
        out.append(_one("empty", t.name, _emptied))
    return out


def _points(t: ArgType) -> list[_Transform]:
    out = _row_classes(t, None, angles=())
    if t.bounds is not None:
        out += [_one("positions at range ends", t.name, _corner(t, up, None)) for up in (1, 0)]
    return out + _order_classes(t)


def _row_classes(t: ArgType, width: int | None, angles: tuple[int, ...]) -> list[_Transform]:
    n = t.name

    def form(outer: str, inner: str) -> Change:
        shape = _row_form(outer, inner)

        def change(v: Any) -> Any:
            rows = _rows(v, width)
            return None if rows is None or not rows else shape(rows)

        return change

    def whole(array: bool) -> Change:
        def change(v: Any) -> Any:
            rows = _rows(v, width)
            if not rows:
                return None
            rounded = []
            for row in rows:
                new = [_round_to(x, _HEADING if i in angles else t) for i, x in enumerate(row)]
                if any(x is None for x in new):
                    return None
                rounded.append(new)
            if array:
                return _np().array(rounded, dtype="int64")
            return _rows_like(rounded, v)

        return change

    out = [_one(label, n, form(outer, inner), pure=True) for label, outer, inner in _ROW_FORMS]
    out.append(_one("ndarray", n, form("ndarray", "float64"), pure=True))
    out.append(_one("whole numbers as int", n, whole(False)))
    out.append(_one("int64 ndarray", n, whole(True)))
    return out


def _wrap(a: float) -> float:
    r = math.remainder(a, 2 * PI)
    return PI if r <= -PI else r


def _inside_positions(rows: list[list[float]], t: ArgType, width: int | None) -> bool:
    if t.bounds is None:
        return True
    cols = 2 if width == 3 else None
    return all(t.contains(x) for row in rows for x in row[:cols])


def _rotate(rows: list[list[float]], rho: float, fixed: dict[int, float]) -> list[list[float]]:
    """Every pose turned by ``rho`` about the origin (a rigid motion of the whole set: the
    poses relative to each other stay the same), headings in (-π, π], some set exactly."""
    c, s = math.cos(rho), math.sin(rho)
    out = []
    for k, (x, y, theta) in enumerate(rows):
        heading = fixed[k] if k in fixed else _wrap(theta + rho)
        out.append([c * x - s * y, s * x + c * y, heading])
    return out


def _rotated_to(t: ArgType, value: float) -> Change:
    """The last pose's heading set to ``value`` by turning the whole set of poses."""

    def change(v: Any) -> Any:
        rows = _rows(v, 3)
        if not rows:
            return None
        last = len(rows) - 1
        moved = _rotate(rows, value - rows[last][2], {last: value})
        return _rows_out(moved, v) if _inside_positions(moved, t, 3) else None

    return change


def _across(t: ArgType) -> Change:
    """The whole set turned so that two consecutive headings lie either side of ±π."""

    def change(v: Any) -> Any:
        rows = _rows(v, 3)
        if not rows or len(rows) < 2:
            return None
        for k in range(len(rows) - 1):
            d = _wrap(rows[k + 1][2] - rows[k][2])
            if 1e-9 < abs(d) < PI - 1e-9:
                first, second = _wrap(PI - d / 2), _wrap(PI + d / 2)
                moved = _rotate(rows, first - rows[k][2], {k: first, k + 1: second})
                return _rows_out(moved, v) if _inside_positions(moved, t, 3) else None
        return None

    return change


def _corner(t: ArgType, upper: int, width: int | None) -> Change:
    """The whole set moved (a translation) until it touches the range's upper (or lower)
    corner: positions of the largest legal magnitude, the same relative geometry."""

    def change(v: Any) -> Any:
        rows = _rows(v, width)
        if not rows or t.bounds is None:
            return None
        low, high = t.bounds
        cols = 2 if width == 3 else len(rows[0])
        shift = []
        for c in range(cols):
            column = [row[c] for row in rows]
            shift.append(high - max(column) if upper else low - min(column))
        moved = [
            [min(max(x + shift[c], low), high) if c < cols else x for c, x in enumerate(row)]
            for row in rows
        ]
        return _rows_out(moved, v) if _inside_positions(moved, t, width) else None

    return change


def _edges(t: ArgType) -> list[_Transform]:
    def form(outer: str, inner: str) -> Change:
        def change(v: Any) -> Any:
            if not isinstance(v, list | tuple) or not v:
                return None
            if not all(isinstance(e, list | tuple) or _is_array(e) for e in v):
                return None
            made = [tuple(e) if inner == "tuple" else list(e) for e in v]
            return tuple(made) if outer == "tuple" else made

        return change

    out = [_one(label, t.name, form(o, i), pure=True) for label, o, i in _ROW_FORMS]
    return out + _order_classes(t)


# ---- matrices


def _matrix_rows(v: Any, t: ArgType) -> list[list[float]] | None:
    rows = _rows(v)
    if not rows:
        return None
    shape = (len(rows), len(rows[0]))
    if t.size is not None and shape != t.size:
        return None
    if t.type != "matrix" and shape[0] != shape[1]:
        return None
    return [[float(x) for x in row] for row in rows]


def _covariance(t: ArgType) -> list[_Transform]:
    n = t.name

    def identity(v: Any) -> Any:
        rows = _matrix_rows(v, t)
        if rows is None:
            return None
        size = len(rows)
        return [[1 if i == j else 0 for j in range(size)] for i in range(size)]

    def whole(array: bool) -> Change:
        def change(v: Any) -> Any:
            rows = _matrix_rows(v, t)
            found = None if rows is None else _whole_psd(rows, t)
            if found is None:
                return None
            if array:
                return _np().array(found, dtype="int64")
            return _rows_like(found, v)

        return change

    out = []
    if t.contains(1.0):
        out.append(_one("identity", n, identity))
    out.append(_one("whole numbers as int", n, whole(False)))
    out.append(_one("int64 ndarray", n, whole(True)))
    out += _matrix_forms(t)
    out.append(_one("large scale", n, _scaled(t, large=True)))
    out.append(_one("small scale", n, _scaled(t, large=False)))
    return out


def _matrix(t: ArgType) -> list[_Transform]:
    n = t.name

    def whole(array: bool) -> Change:
        def change(v: Any) -> Any:
            rows = _matrix_rows(v, t)
            if rows is None:
                return None
            rounded = [[_round_to(x, t) for x in row] for row in rows]
            if any(x is None for row in rounded for x in row):
                return None
            if array:
                return _np().array(rounded, dtype="int64")
            return _rows_like(rounded, v)

        return change

    out = _matrix_forms(t)
    out.append(_one("whole numbers as int", n, whole(False)))
    out.append(_one("int64 ndarray", n, whole(True)))
    if t.bounds is not None:
        out.append(_one("largest magnitudes", n, _largest(t)))
    return out


def _matrix_forms(t: ArgType) -> list[_Transform]:
    def change_to(form: str) -> Change:
        def change(v: Any) -> Any:
            rows = _matrix_rows(v, t)
            if rows is None:
                return None
            return rows if form == "list" else _np().array(rows, dtype="float64")

        return change

    return [
        _one("list of lists", t.name, change_to("list"), pure=True),
        _one("ndarray", t.name, change_to("ndarray"), pure=True),
    ]


def _positive_definite(rows: list[list[float]]) -> bool:
    np = _np()
    m = np.array(rows, dtype="float64")
    if not np.array_equal(m, m.T):
        return False
    return bool(np.linalg.eigvalsh(m).min() > 0)


def _whole_psd(rows: list[list[float]], t: ArgType) -> list[list[int]] | None:
    """A symmetric positive definite matrix of whole numbers like ``rows``: ``rows`` rounded,
    else ``rows`` scaled until its smallest variance is 4 and rounded, else its rounded
    diagonal (at least 1); each with its diagonal inside the declared range."""
    size = len(rows)
    diagonal = [rows[i][i] for i in range(size)]
    candidates = [rows]
    if min(diagonal) > 0:
        s = 4 / min(diagonal)
        candidates.append([[x * s for x in row] for row in rows])
    candidates.append(
        [[max(1.0, diagonal[i]) if i == j else 0.0 for j in range(size)] for i in range(size)]
    )
    for candidate in candidates:
        rounded = [[math.floor(x + 0.5) for x in row] for row in candidate]
        if not all(t.contains(rounded[i][i]) for i in range(size)):
            continue
        if _positive_definite([[float(x) for x in row] for row in rounded]):
            return [[int(x) for x in row] for row in rounded]
    return None


def _scaled(t: ArgType, *, large: bool) -> Change:
    """The matrix times a positive factor (still positive semidefinite): its largest variance
    at the top of the range (its smallest at the bottom), or a factor of 1000 (1/1000)."""

    def change(v: Any) -> Any:
        rows = _matrix_rows(v, t)
        if rows is None:
            return None
        diagonal = [rows[i][i] for i in range(len(rows))]
        factor = _SCALE if large else 1 / _SCALE
        if t.bounds is not None:
            low, high = t.bounds
            if large and max(diagonal) > 0:
                factor = high / max(diagonal)
            elif not large and low > 0 and min(diagonal) > 0:
                factor = low / min(diagonal)
        scaled = [[x * factor for x in row] for row in rows]
        if t.bounds is not None:  # the end reached exactly, not an ulp beyond
            low, high = t.bounds
            for i in range(len(rows)):
                if low * (1 - 1e-12) <= scaled[i][i] <= high * (1 + 1e-12):
                    scaled[i][i] = min(max(scaled[i][i], low), high)
                else:
                    return None
        if _is_array(v):
            return _np().array(scaled, dtype="float64")
        return _rows_like(scaled, v)

    return change


def _largest(t: ArgType) -> Change:
    """A general matrix scaled until an entry reaches an end of the range."""

    def change(v: Any) -> Any:
        rows = _matrix_rows(v, t)
        if rows is None or t.bounds is None:
            return None
        low, high = t.bounds
        factors = []
        for x in (x for row in rows for x in row):
            if x > 0 and high > 0:
                factors.append(high / x)
            elif x < 0 and low < 0:
                factors.append(low / x)
        if not factors:
            return None
        factor = min(factors)
        scaled = [[min(max(x * factor, low), high) for x in row] for row in rows]
        if not all(t.contains(x) for row in scaled for x in row):
            return None
        if _is_array(v):
            return _np().array(scaled, dtype="float64")
        return _rows_like(scaled, v)

    return change


# ---- rotations and 3-D poses

ORTHONORMAL = 1e-9
"""How far ``RᵀR`` of a ``rotation`` (and of a ``pose3``'s rotation block) may be from ``I``."""
SMALL_TURNS = (1e-9, 1e-3)
"""Angles of the ``small angle`` rotations (rad): ``cos θ`` rounds to 1 at the first."""
UNDER_PI = (1e-7, 1e-12)
"""How far below π the ``just under π`` rotations turn (the antisymmetric part ``~ π − θ``)."""


def rotation_problem(rows: Any) -> str | None:
    """Why ``rows`` is not a rotation matrix (3 × 3 numbers, ``RᵀR = I`` to
    :data:`ORTHONORMAL`, determinant positive), or None. Pure Python: examples are checked
    when an exercise loads."""
    m = _square(rows, 3)
    if m is None:
        return "is not a 3 × 3 matrix of numbers"
    if not all(math.isfinite(x) for row in m for x in row):
        return "has entries that are not finite"
    worst = max(
        abs(sum(m[k][i] * m[k][j] for k in range(3)) - (1.0 if i == j else 0.0))
        for i in range(3)
        for j in range(3)
    )
    if worst > ORTHONORMAL:
        return f"is not a rotation: RᵀR differs from I by {worst:.3g} (at most {ORTHONORMAL:g})"
    if _det3(m) <= 0:
        return "is a reflection (determinant −1), not a rotation"
    return None


def pose3_problem(rows: Any, t: ArgType | None = None) -> str | None:
    """Why ``rows`` is not a 3-D pose (a 4 × 4 ``[[R, t], [0, 0, 0, 1]]``, ``R`` a rotation,
    ``t`` inside ``t``'s range if declared), or None. Pure Python."""
    m = _square(rows, 4)
    if m is None:
        return "is not a 4 × 4 matrix of numbers"
    if m[3] != [0.0, 0.0, 0.0, 1.0]:
        return "has a last row other than [0, 0, 0, 1]"
    why = rotation_problem([row[:3] for row in m[:3]])
    if why is not None:
        return f"has a rotation block that {why}"
    if t is not None and not all(t.contains(m[i][3]) for i in range(3)):
        assert t.bounds is not None
        low, high = t.bounds
        return f"has a translation outside the declared range [{low:g}, {high:g}]"
    return None


def _square(v: Any, n: int) -> list[list[float]] | None:
    """An n × n matrix (nested sequences or a 2-D array) as rows of floats, or None."""
    rows = _rows(v, n)
    if rows is None or len(rows) != n:
        return None
    return [[float(x) for x in row] for row in rows]


def _det3(m: list[list[float]]) -> float:
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


Turn = Callable[[list[list[float]]], "list[list[float]] | None"]  # a rotation's new rotation


def _rotation(t: ArgType) -> list[_Transform]:
    return [
        *_rotation_classes(t),
        _one("whole numbers as int", t.name, _whole_turn(t, array=False)),
        _one("int64 ndarray", t.name, _whole_turn(t, array=True)),
        _one("list of lists", t.name, _turn_form(t, "list"), pure=True),
        _one("ndarray", t.name, _turn_form(t, "ndarray"), pure=True),
    ]


def _pose3(t: ArgType) -> list[_Transform]:
    out = _rotation(t)
    if t.bounds is not None:
        for upper in (True, False):
            out.append(_one("translation at range ends", t.name, _translation_end(t, upper)))
    return out


def _rotation_classes(t: ArgType) -> list[_Transform]:
    """The classes of a rotation (of a pose's rotation block, the translation kept)."""
    n = t.name
    out = [_one("identity", n, _turned(t, lambda _r: _IDENTITY))]
    out += [_one("small angle", n, _turned(t, _about_own_axis(a))) for a in SMALL_TURNS]
    out.append(_one("half turn", n, _turned(t, _half_turn)))
    out += [_one("just under π", n, _turned(t, _about_own_axis(PI - d))) for d in UNDER_PI]
    return out


_IDENTITY = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]


def _split(v: Any, t: ArgType) -> tuple[list[list[float]], list[float] | None] | None:
    """A rotation (or a pose's rotation block and translation) in the type's domain, or None."""
    if t.type == "pose3":
        m = _square(v, 4)
        if m is None or pose3_problem(m, t) is not None:
            return None
        return [row[:3] for row in m[:3]], [row[3] for row in m[:3]]
    m = _square(v, 3)
    if m is None or rotation_problem(m) is not None:
        return None
    return m, None


def _joined(r: list[list[Any]], translation: list[Any] | None) -> list[list[Any]]:
    if translation is None:
        return [list(row) for row in r]
    zero, one = (0, 1) if all(type(x) is int for row in r for x in row) else (0.0, 1.0)
    rows = [[*r[i], translation[i]] for i in range(3)]
    return [*rows, [zero, zero, zero, one]]


def _turned(t: ArgType, turn: Turn) -> Change:
    """The rotation (block) replaced by ``turn`` of it, in the base's container (an array
    stays a float array); None where the base is not in the domain or the result is not."""

    def change(v: Any) -> Any:
        parts = _split(v, t)
        if parts is None:
            return None
        r = turn(parts[0])
        if r is None or rotation_problem(r) is not None:  # the built-in domain check
            return None
        return _rows_out(_joined(r, parts[1]), v)

    return change


def _axis(r: list[list[float]]) -> list[float] | None:
    """The unit axis of a rotation, turning the way it turns (at exactly π, its largest
    component positive); None for the identity (no axis)."""
    np = _np()
    m = np.array(r, dtype="float64")
    v = np.array([m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]])
    size = float(np.linalg.norm(v))
    if np.trace(m) > 1 or size > 1e-3:  # away from π, 2 sin θ n is accurate
        return None if size == 0 else (v / size).tolist()
    _, vectors = np.linalg.eigh((m + m.T) / 2)  # near π: the eigenvalue 1 of the symmetric part
    axis = vectors[:, -1]
    side = float(axis @ v)
    if side < 0 or (side == 0 and axis[int(np.argmax(np.abs(axis)))] < 0):
        axis = -axis
    out: list[float] = (axis / np.linalg.norm(axis)).tolist()
    return out


def _exp(axis: list[float], angle: float) -> list[list[float]]:
    """Rodrigues: the rotation by ``angle`` about the unit ``axis``."""
    np = _np()
    x, y, z = axis
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    r = np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)
    out: list[list[float]] = r.tolist()
    return out


def _about_own_axis(angle: float) -> Turn:
    def turn(r: list[list[float]]) -> list[list[float]] | None:
        axis = _axis(r)
        return None if axis is None else _exp(axis, angle)

    return turn


def _half_turn(r: list[list[float]]) -> list[list[float]] | None:
    """``2 n nᵀ − I`` about the rotation's own axis: exactly symmetric (``n_i n_j = n_j n_i``
    in floating point), so no antisymmetric part tells ``π n`` from ``−π n``."""
    axis = _axis(r)
    if axis is None:
        return None
    return [[2 * axis[i] * axis[j] - (1.0 if i == j else 0.0) for j in range(3)] for i in range(3)]


def _signed_permutations() -> list[list[list[int]]]:
    """The 24 rotations whose entries are whole numbers (signed permutation matrices of
    determinant +1), the identity first."""
    import itertools

    found = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1, -1), repeat=3):
            m = [[signs[i] if j == perm[i] else 0 for j in range(3)] for i in range(3)]
            if _det3([[float(x) for x in row] for row in m]) > 0:
                found.append(m)
    return found


def _whole_turn(t: ArgType, *, array: bool) -> Change:
    """The rotation with whole-number entries nearest to the base's (the identity aside: it
    is a class of its own), a pose's translation rounded into its range; Python ints in the
    base's containers, or an int64 array."""

    def change(v: Any) -> Any:
        parts = _split(v, t)
        if parts is None:
            return None
        r, translation = parts
        turns = _signed_permutations()[1:]
        best = max(turns, key=lambda p: sum(p[i][j] * r[i][j] for i in range(3) for j in range(3)))
        moved = None
        if translation is not None:
            moved = [_round_to(x, t) for x in translation]
            if any(x is None for x in moved):
                return None
        rows = _joined(best, moved)
        if array:
            return _np().array(rows, dtype="int64")
        return _rows_like(rows, v)

    return change


def _turn_form(t: ArgType, form: str) -> Change:
    def change(v: Any) -> Any:
        parts = _split(v, t)
        if parts is None:
            return None
        rows = _joined(*parts)
        return rows if form == "list" else _np().array(rows, dtype="float64")

    return change


def _translation_end(t: ArgType, upper: bool) -> Change:
    """A pose's translation set to the range's upper (or lower) end in every coordinate."""

    def change(v: Any) -> Any:
        parts = _split(v, t)
        if parts is None or t.bounds is None:
            return None
        end = float(t.bounds[1] if upper else t.bounds[0])
        return _rows_out(_joined(parts[0], [end, end, end]), v)

    return change


# ---- text


def _text(t: ArgType) -> list[_Transform]:
    n = t.name
    out = [
        _one("CRLF line ends", n, _crlf, pure=True),
        _one("no final newline", n, _no_final_newline, pure=True),
        _one("blank lines and trailing spaces", n, _padded, pure=True),
    ]
    if t.type in ("g2o", "edge3"):
        out.append(_one("exponent notation", n, _exponents, pure=True))
    if t.type == "g2o":  # EDGE3 text has no vertices to put an edge before
        out.append(_one("edge line first", n, _edge_first, pure=True))
    return out


def _crlf(text: Any) -> Any:
    if not isinstance(text, str):
        return None
    return text.replace("\r\n", "\n").replace("\n", "\r\n")


def _no_final_newline(text: Any) -> Any:
    return text.rstrip("\r\n") if isinstance(text, str) else None


def _newline(text: str) -> str:
    return "\r\n" if "\r\n" in text else "\n"


def _padded(text: Any) -> Any:
    """A blank line first and after the first line, two spaces at the end of every line."""
    if not isinstance(text, str):
        return None
    newline = _newline(text)
    lines = text.splitlines(keepends=True)
    out = [newline]
    for i, line in enumerate(lines):
        body = line.rstrip("\r\n")
        out.append(body + "  " + line[len(body) :])
        if i == 0 and line != body:
            out.append(newline)
    return "".join(out)


_TOKENS = re.compile(r"(\s+)")


def _exponents(text: Any) -> Any:
    """Every number after a g2o line's tag and ids written in exponent notation, the same
    value (``0.774115`` → ``7.74115e-01``); ids, tags and separators unchanged."""
    if not isinstance(text, str):
        return None
    out = []
    for line in text.splitlines(keepends=True):
        body = line.rstrip("\r\n")
        parts = _TOKENS.split(body)
        words = [i for i, p in enumerate(parts) if p and not p.isspace()]
        if words:
            tag = parts[words[0]].upper()
            ids = 1 if tag.startswith("VERTEX") else 2 if tag.startswith("EDGE") else None
            if ids is not None:
                for i in words[1 + ids :]:
                    parts[i] = _exponent(parts[i])
        out.append("".join(parts) + line[len(body) :])
    return "".join(out)


def _exponent(token: str) -> str:
    try:
        x = float(token)
    except ValueError:
        return token
    if not math.isfinite(x):
        return token
    for digits in range(17):
        text = f"{x:.{digits}e}"
        if float(text) == x:
            return text
    return repr(x)


def _edge_first(text: Any) -> Any:
    """The first EDGE line moved to the start (vertices and edges may come in any order; the
    edges keep their order); the text itself when an edge already comes first."""
    if not isinstance(text, str):
        return None
    lines = text.splitlines(keepends=True)
    tags = [(line.split() or [""])[0].upper() for line in lines]
    vertex = next((i for i, tag in enumerate(tags) if tag.startswith("VERTEX")), None)
    edge = next((i for i, tag in enumerate(tags) if tag.startswith("EDGE")), None)
    if vertex is None or edge is None:
        return None
    if edge < vertex:
        return text
    newline = _newline(text)
    moved = lines.pop(edge)
    if not moved.endswith(("\n", "\r")):
        moved += newline
        lines[-1] = lines[-1].rstrip("\r\n")
    return moved + "".join(lines)


# ---- pairs of headings


def _angle_slots(types: tuple[ArgType, ...]) -> list[tuple[ArgType, int | None, str]]:
    """Arguments (or entries of them) that hold one heading: (type, entry or None, name)."""
    slots: list[tuple[ArgType, int | None, str]] = []
    for t in types:
        if t.type == "angle" and all(t.contains(PI - d) and t.contains(d - PI) for d in ACROSS):
            slots.append((t, None, t.name))
        elif t.type == "pose":
            slots.append((t, 2, t.name))
        elif t.type == "vector":
            slots += [(t, i, f"{t.name}[{i}]") for i in t.angles]
    return slots


def _pairs(types: tuple[ArgType, ...]) -> list[_Transform]:
    """Two heading-bearing arguments (two poses, a pose and a measurement, …) set just either
    side of ±π, so that their difference crosses ±π; their other entries are the base's."""
    slots = _angle_slots(types)
    out = []
    for i, (a, a_entry, a_name) in enumerate(slots):
        for b, b_entry, b_name in slots[i + 1 :]:
            if a.name == b.name:
                continue
            label = f"headings across ±π ({a_name}, {b_name})"
            for delta in ACROSS:
                for sign in (1.0, -1.0):
                    first, second = sign * (PI - delta), -sign * (PI - delta)
                    out.append(
                        _Transform(
                            label,
                            _pair(a.name, a_entry, first, b.name, b_entry, second),
                            False,
                        )
                    )
    return out


def _pair(
    a: str, a_entry: int | None, a_value: float, b: str, b_entry: int | None, b_value: float
) -> Make:
    def put(value: Any, entry: int | None, x: float) -> Any:
        if entry is None:
            return x if _number(value) is not None else None
        return _set_entry(entry, x)(value)

    def make(kwargs: dict[str, Any]) -> dict[str, Any] | None:
        new_a, new_b = put(kwargs[a], a_entry, a_value), put(kwargs[b], b_entry, b_value)
        if new_a is None or new_b is None:
            return None
        out = dict(kwargs)
        out[a], out[b] = new_a, new_b
        return out

    return make


_BUILDERS: dict[str, Callable[[ArgType], list[_Transform]]] = {
    "real": _real,
    "angle": _angle,
    "count": _count,
    "probability": _probability,
    "vector": _vector,
    "pose": _pose,
    "poses": _poses,
    "points": _points,
    "covariance": _covariance,
    "information": _covariance,
    "matrix": _matrix,
    "indices": _indices,
    "edges": _edges,
    "rotation": _rotation,
    "pose3": _pose3,
    "g2o": _text,
    "edge3": _text,
    "text": _text,
}


# ------------------------------------------------------------------------------ values


def _np() -> Any:
    import numpy

    return numpy


def _is_array(v: Any) -> bool:
    np = sys.modules.get("numpy")
    return np is not None and isinstance(v, np.ndarray)


def _number(x: Any) -> int | float | None:
    """``x`` as a Python number (numpy scalars too), or None for anything else."""
    if isinstance(x, bool):
        return None
    if isinstance(x, int | float):
        return x
    np = sys.modules.get("numpy")
    if np is not None and isinstance(x, np.generic) and x.dtype.kind in "iuf":
        value = x.item()
        return value if isinstance(value, int | float) else None
    return None


def _key(v: Any) -> Any:
    """A key equal for two values exactly when their values *and* types are equal."""
    if isinstance(v, bool):
        return ("b", v)
    if isinstance(v, int):
        return ("i", v)
    if isinstance(v, float):
        return ("f", v.hex())
    if isinstance(v, str):
        return ("s", v)
    if isinstance(v, tuple):
        return ("t", tuple(_key(x) for x in v))
    if isinstance(v, list):
        return ("l", tuple(_key(x) for x in v))
    if isinstance(v, dict):
        return ("d", tuple(sorted((str(k), _key(x)) for k, x in v.items())))
    if _is_array(v):
        return ("a", v.dtype.str, v.shape, v.tobytes())
    return ("o", type(v).__name__, repr(v))


def _score(kwargs: dict[str, Any]) -> float:
    """How far from trivial an input is: the share of its numbers that are nonzero plus the
    share that are not whole (0 for an input without numbers)."""
    numbers: list[float] = []
    _collect(kwargs, numbers, 4000)
    if not numbers:
        return 0.0
    nonzero = sum(1 for x in numbers if x != 0)
    fractional = sum(1 for x in numbers if math.isfinite(x) and x != math.floor(x))
    return (nonzero + fractional) / len(numbers)


def _only_empty_changed(base: dict[str, Any], out: dict[str, Any]) -> bool:
    """Whether every argument a transform changed is empty (``[]`` given as a tuple or an
    array: another form, but nothing a function could get wrong in it)."""
    changed = [n for n in out if out[n] is not base.get(n)]  # (a transform keeps the others)
    return bool(changed) and all(_length(out[n]) == 0 for n in changed)


def _length(v: Any) -> int | None:
    try:
        return len(v)
    except TypeError:
        return None


def input_size(v: Any) -> int:
    """How large an input is: its numbers, plus a text's length in eights (about one number
    per eight characters), containers summed."""
    if isinstance(v, str):
        return 1 + len(v) // 8
    if isinstance(v, dict):
        return sum(input_size(x) for x in v.values())
    if isinstance(v, list | tuple):
        return sum(input_size(x) for x in v)
    if _is_array(v):
        return max(1, int(v.size))
    return 1


def _collect(v: Any, out: list[float], cap: int) -> None:
    if len(out) >= cap:
        return
    n = _number(v)
    if n is not None:
        out.append(float(n))
    elif isinstance(v, dict):
        for x in v.values():
            _collect(x, out, cap)
    elif isinstance(v, list | tuple):
        for x in v:
            _collect(x, out, cap)
    elif _is_array(v) and v.dtype.kind in "iuf":
        out += [float(x) for x in v.ravel()[: cap - len(out)].tolist()]


# ------------------------------------------------------------------------------ parsing


def parse_types(
    raw: Any, signature: Sequence[str], check: Checker, *, line: int = 0
) -> tuple[ArgType, ...]:
    """The ``types:`` mapping of an exercise (``raw``; ``line``: the line of the key), one
    :class:`ArgType` per signature parameter, in the signature's order. Every mistake is a
    problem of ``check`` at its line, saying how to fix it."""
    if not isinstance(raw, dict) or not raw:
        check.add(
            line,
            "'types' must map every parameter to its type, e.g. 'a: angle' or "
            f"'n: {{type: count, range: [1, 30]}}', not {raw!r}",
        )
        return ()
    found: dict[str, ArgType] = {}
    for name, value in raw.items():
        at = _line_of(raw, name, line)
        if name not in signature:
            check.add(
                at,
                f"'types' names '{name}', which is not a parameter{_did_you_mean(name, signature)}"
                f"; the signature is ({', '.join(signature)})",
            )
            continue
        parsed = _parse_one(str(name), value, at, check)
        if parsed is not None:
            found[name] = parsed
    missing = [n for n in signature if n not in raw]
    if missing:
        check.add(
            line,
            f"'types' gives no type for {', '.join(repr(n) for n in missing)}: declare every "
            f"parameter, e.g. '{missing[0]}: real' (types: {', '.join(TYPES)}; 'data' for one "
            "without boundary inputs)",
        )
    return tuple(found[n] for n in signature if n in found)


def _parse_one(name: str, value: Any, line: int, check: Checker) -> ArgType | None:
    what = f"the type of '{name}'"
    if isinstance(value, str):
        kind, params = value, {}
    elif isinstance(value, dict):
        if "type" not in value:
            check.add(
                line,
                f"{what} needs 'type: <name>', e.g. '{name}: {{type: real, range: [0, 1]}}' "
                f"(types: {', '.join(TYPES)})",
            )
            return None
        kind, params = value["type"], {k: v for k, v in value.items() if k != "type"}
    else:
        check.add(
            line,
            f"{what} must be a type name such as 'angle' or a mapping such as "
            f"'{{type: real, range: [0, 1]}}', not {value!r}",
        )
        return None
    if not isinstance(kind, str) or kind not in TYPES:
        check.add(
            _line_of(value, "type", line),
            f"unknown type {str(kind)!r} for '{name}'{_did_you_mean(str(kind), TYPES)}; "
            f"known types: {', '.join(TYPES)}",
        )
        return None
    allowed = _PARAMETERS[kind]
    fields: dict[str, Any] = {}
    ok = True
    for key, item in params.items():
        at = _line_of(value, key, line)
        if key not in allowed:
            takes = f"it takes {', '.join(allowed)}" if allowed else "it takes no parameters"
            check.add(
                at,
                f"'{key}' does not apply to type '{kind}' of '{name}'"
                f"{_did_you_mean(str(key), allowed)}; {takes}",
            )
            ok = False
            continue
        parsed = _PARAMETER_PARSERS[key](item, kind, f"'{key}' of '{name}'", at, check)
        if parsed is None:
            ok = False
        else:
            fields[_FIELD[key]] = parsed
    if kind == "count" and "bounds" not in fields and "range" not in params:
        check.add(
            line,
            f"type 'count' of '{name}' needs its range, the smallest and largest value the "
            f"prompt allows: write '{name}: {{type: count, range: [1, 100]}}'",
        )
        ok = False
    t = ArgType(name, kind, line=line, **fields)
    if t.length is not None and (t.ties or t.empty):
        check.add(
            line,
            f"'{name}' has a fixed 'length', so 'ties' and 'empty' (which change it) cannot "
            "apply; remove one",
        )
        ok = False
    if t.length is not None and any(i >= t.length for i in t.angles):
        check.add(line, f"'angles' of '{name}' names an entry beyond its length {t.length}")
        ok = False
    if t.bounds is None and kind in _DEFAULT_BOUNDS:
        t = replace(t, bounds=_DEFAULT_BOUNDS[kind])
    return t if ok else None


_DEFAULT_BOUNDS = {"angle": (-PI, PI), "probability": (0.0, 1.0)}


_FIELD = {
    "range": "bounds",
    "open": "open",
    "length": "length",
    "size": "size",
    "angles": "angles",
    "ordered": "ordered",
    "ties": "ties",
    "empty": "empty",
}


def _parse_range(
    value: Any, kind: str, what: str, line: int, check: Checker
) -> tuple[float, float] | None:
    whole = kind == "count"
    ends: list[float] = []
    if isinstance(value, list | tuple) and len(value) == 2:
        for end in value:
            number = _range_end(end, whole)
            if number is None:
                break
            ends.append(number)
    form = "two whole numbers" if whole else "two numbers (or formulas such as -pi, 2*pi)"
    if len(ends) != 2:
        check.add(line, f"{what} must be [low, high]: {form}, not {value!r}")
        return None
    low, high = ends
    if low > high or (low == high and not whole):
        check.add(line, f"{what} must have low < high, not [{low:g}, {high:g}]")
        return None
    if kind == "probability" and not 0 <= low <= high <= 1:
        check.add(line, f"{what} must lie within [0, 1], not [{low:g}, {high:g}]")
        return None
    return (low, high)


def _range_end(end: Any, whole: bool) -> float | None:
    if isinstance(end, bool):
        return None
    if whole:
        return end if isinstance(end, int) else None
    if isinstance(end, int | float):
        return float(end) if math.isfinite(end) else None
    if isinstance(end, str):
        from slamcourse.answers import evaluate_number

        try:
            number = evaluate_number(end)
        except Exception:  # any unreadable formula: reported by the caller
            return None
        return number if math.isfinite(number) else None
    return None


def _parse_open(value: Any, kind: str, what: str, line: int, check: Checker) -> str | None:
    if value in _OPEN:
        return str(value)
    check.add(line, f"{what} must be one of {', '.join(_OPEN)} (the excluded ends), not {value!r}")
    return None


def _whole_number(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= 1


def _parse_length(value: Any, kind: str, what: str, line: int, check: Checker) -> int | None:
    if _whole_number(value):
        return int(value)
    check.add(line, f"{what} must be a whole number of at least 1, not {value!r}")
    return None


def _parse_size(
    value: Any, kind: str, what: str, line: int, check: Checker
) -> tuple[int, int] | None:
    if _whole_number(value):
        return (int(value), int(value))
    if (
        kind == "matrix"
        and isinstance(value, list)
        and len(value) == 2
        and all(_whole_number(v) for v in value)
    ):
        return (int(value[0]), int(value[1]))
    form = "a whole number n (an n × n matrix)"
    if kind == "matrix":
        form += " or [rows, cols]"
    check.add(line, f"{what} must be {form}, not {value!r}")
    return None


def _parse_angles(
    value: Any, kind: str, what: str, line: int, check: Checker
) -> tuple[int, ...] | None:
    if isinstance(value, list) and all(
        isinstance(v, int) and not isinstance(v, bool) and v >= 0 for v in value
    ):
        return tuple(sorted(set(value)))
    check.add(line, f"{what} must list the entries that are angles, e.g. [1], not {value!r}")
    return None


def _parse_flag(value: Any, kind: str, what: str, line: int, check: Checker) -> bool | None:
    if isinstance(value, bool):
        return value
    check.add(line, f"{what} must be true or false, not {value!r}")
    return None


_PARAMETER_PARSERS: dict[str, Callable[[Any, str, str, int, Checker], Any]] = {
    "range": _parse_range,
    "open": _parse_open,
    "length": _parse_length,
    "size": _parse_size,
    "angles": _parse_angles,
    "ordered": _parse_flag,
    "ties": _parse_flag,
    "empty": _parse_flag,
}


def parse_valid(value: Any, line: int, check: Checker) -> str | None:
    """``valid: <function in reference.py>``: it takes an input's keyword arguments and says
    whether the input lies in the exercise's domain (derived boundary inputs it rejects are
    dropped). Its existence is checked where it is used, like ``strategy``."""
    if value is None:
        return None
    if isinstance(value, str) and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", value):
        return value
    check.add(
        line,
        f"'valid' must name a function in reference.py that takes the inputs as keyword "
        f"arguments and returns True when they are in the domain, not {value!r}",
    )
    return None


def parse_mutates(
    value: Any, line: int, signature: Sequence[str], check: Checker
) -> tuple[str, ...]:
    """``mutates: [name, …]``: the parameters the prompt allows the function to change in
    place (by default none)."""
    if value is None:
        return ()
    items = [value] if isinstance(value, str) else value
    if not isinstance(items, list):
        check.add(line, f"'mutates' must list parameter names, e.g. [grid], not {value!r}")
        return ()
    names: list[str] = []
    for item in items:
        if not isinstance(item, str) or item not in signature:
            check.add(
                line,
                f"'mutates' names {item!r}, which is not a parameter"
                f"{_did_you_mean(str(item), signature)}; the signature is "
                f"({', '.join(signature)})",
            )
        elif item in names:
            check.add(line, f"'mutates' names '{item}' twice")
        else:
            names.append(item)
    return tuple(names)


def types_from_arguments(arguments: Iterable[Any]) -> tuple[ArgType, ...]:
    """Types for an exercise without ``types:``, from its ``arguments:`` ranges
    (:class:`~slamcourse.grading.strategies.Argument`): ``float`` → real, ``int`` → count,
    ``choice`` → choice, each with the declared range."""
    found = []
    for arg in arguments:
        if arg.dist == "float":
            found.append(ArgType(arg.name, "real", (float(arg.args[0]), float(arg.args[1]))))
        elif arg.dist == "int":
            found.append(ArgType(arg.name, "count", (int(arg.args[0]), int(arg.args[1]))))
        else:
            found.append(ArgType(arg.name, "choice"))
    return tuple(found)


def outside(t: ArgType, value: Any) -> str | None:
    """Why an example's ``value`` lies outside a scalar type's declared domain, or None (other
    types are not checked here: their boundary transforms skip a value of another shape); a
    ``rotation`` or a ``pose3`` is checked by its built-in domain check
    (:func:`rotation_problem`, :func:`pose3_problem`)."""
    if t.type in ("rotation", "pose3"):
        why = rotation_problem(value) if t.type == "rotation" else pose3_problem(value, t)
        return None if why is None else f"the matrix {why} (type {t.type})"
    if t.type not in _SCALARS:
        return None
    number = _number(value)
    if number is None:
        return f"{value!r} is not a number"
    if t.type == "count" and not isinstance(number, int):
        return f"{value!r} is not a whole number (type count)"
    if not t.contains(number):
        assert t.bounds is not None
        low, high = t.bounds
        ends = ("(" if t.open in ("low", "both") else "[") + f"{low:g}, {high:g}"
        ends += ")" if t.open in ("high", "both") else "]"
        return (
            f"{value!r} is outside the declared range {ends} of type {t.type}; widen the "
            "range in 'types' or fix the example"
        )
    return None


def assumptions(arguments: Iterable[Any], assume: Sequence[str]) -> Callable[..., bool] | None:
    """A check of an exercise's ``assume:`` conditions on one input's keyword arguments (for
    derived inputs of an exercise drawn from ``arguments:``), or None when it has none."""
    if not assume:
        return None
    from slamcourse.answers import compile_expression
    from slamcourse.grading.strategies import _holds

    names = [a.name for a in arguments]
    checks = [compile_expression(text, names, logic=True) for text in assume]

    def holds(**kwargs: Any) -> bool:
        try:
            return bool(_holds(checks, kwargs))
        except Exception:  # a condition that cannot be evaluated on this input: not satisfied
            return False

    return holds


def _line_of(data: Any, key: Any, default: int) -> int:
    line_of = getattr(data, "line_of", None)
    if callable(line_of):
        found = line_of(key)
        return found if isinstance(found, int) and found else default
    return default


def _did_you_mean(word: str, known: Iterable[str]) -> str:
    import difflib

    close = difflib.get_close_matches(word, sorted(known), n=1, cutoff=0.6)
    return f" (did you mean {close[0]}?)" if close else ""
