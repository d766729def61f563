"""The grouped comparison (``returns.accepted``): every value it clears at once is one the
one-by-one rule (``compare``) accepts, for every return form and every kind of entry a learner
can send; and right values of the ordinary kind are cleared, so the fast path is taken."""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from slamcourse.grading.returns import Tolerance, accepted, compare, numeric_array

TOLS = st.sampled_from([Tolerance(), Tolerance(rtol=1e-6, atol=1e-9), Tolerance(0.0, 0.5)])
PI = math.pi
scalar = st.one_of(
    st.floats(-1e6, 1e6),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from(
        [PI, -PI, math.nextafter(PI, 4), math.nextafter(-PI, -4), 2 * PI, 0.0, -0.0, 1e300]
    ),
    st.integers(-(10**6), 10**6),
    st.integers(10**308, 10**310),  # beyond floats
    st.booleans(),
    st.none(),
)


def near(value: object) -> st.SearchStrategy[object]:
    """A value like ``value``: itself, nudged within or just past a tolerance, wrapped by 2π,
    or anything at all."""
    if isinstance(value, list):
        return st.one_of(st.lists(scalar, max_size=4), st.tuples(*map(near, value)).map(list))
    if type(value) in (int, float) and math.isfinite(value):
        v = float(value)
        return st.one_of(
            st.just(value),
            st.sampled_from([v + 2 * PI, v - 2 * PI, v * (1 + 0.01), v + 1e-9, round(v)]),
            st.floats(-1e-2, 1e-2).map(lambda d: v + d),
            scalar,
        )
    return scalar


@st.composite
def groups(draw: st.DrawFn) -> tuple[object, list[object], list[object]]:
    spec = draw(
        st.one_of(
            st.sampled_from(["number", "integer", "angle", "boolean", "array"]),
            st.lists(st.sampled_from(["number", "integer", "angle"]), min_size=1, max_size=3).map(
                tuple
            ),
        )
    )
    n = draw(st.integers(1, 6))
    if spec == "array":
        rows, cols = draw(st.integers(0, 3)), draw(st.none() | st.integers(0, 3))
        entry = st.floats(-10, 10)
        row = st.lists(entry, min_size=rows, max_size=rows)
        if cols is None:
            wants = [draw(row) for _ in range(n)]
        else:
            line = st.lists(entry, min_size=cols, max_size=cols)
            wants = [draw(st.lists(line, min_size=rows, max_size=rows)) for _ in range(n)]
    elif isinstance(spec, tuple):
        wants = [draw(st.lists(st.floats(-PI, PI), min_size=len(spec), max_size=len(spec)))]
        wants += [draw(st.just(wants[0])) for _ in range(n - 1)]
    elif spec == "boolean":
        wants = draw(st.lists(st.booleans(), min_size=n, max_size=n))
    else:
        values_of = st.floats(-PI, PI) if spec == "angle" else st.floats(-50, 50)
        wants = draw(st.lists(values_of | st.integers(-3, 3), min_size=n, max_size=n))
    values = [draw(near(w)) for w in wants]
    return spec, values, wants


@given(groups(), TOLS)
def test_every_value_cleared_is_accepted_one_by_one(
    group: tuple[object, list[object], list[object]], tol: Tolerance
) -> None:
    spec, values, wants = group
    arrays = [numeric_array(w) for w in wants] if spec == "array" else None
    for as_sent in (None, [sent_as_bytes(v) for v in values]):
        for cleared, got, want in zip(
            accepted(spec, values, wants, tol, arrays, as_sent), values, wants, strict=True
        ):
            if cleared:
                assert compare(spec, got, want, tol, plain=True) is None, (spec, got, want)


def sent_as_bytes(value: object) -> object:
    """The ndarray a value of floats comes with from the sandbox (``CallResult.array``: a
    float array, not empty, whose lists the value is), else None."""
    array = numeric_array(value)
    if array is None or not array.size or array.tolist() != value:
        return None
    return array


@given(groups(), TOLS)
def test_right_values_are_cleared_at_once(
    group: tuple[object, list[object], list[object]], tol: Tolerance
) -> None:
    spec, _values, wants = group
    # the reference's own values, as a correct function returns them
    values = [w if not isinstance(w, list) else list(w) for w in wants]
    if spec == "integer":
        wants = values = [round(w) for w in wants]
    if isinstance(spec, tuple):  # (an integer part is a whole number)
        wants = values = [
            [round(x) if kind == "integer" else x for kind, x in zip(spec, w, strict=True)]
            for w in wants
        ]
    if spec == "array" and len({str(numeric_array(w).shape) for w in wants}) > 1:
        return
    assert accepted(spec, values, wants, tol) == [True] * len(values)
    as_sent = [sent_as_bytes(v) for v in values]
    assert accepted(spec, values, wants, tol, None, as_sent) == [True] * len(values)


def test_what_is_left_to_the_one_by_one_rule() -> None:
    tol = Tolerance()
    # an angle off by a turn is right, but only the one-by-one rule wraps it
    assert accepted("angle", [PI + 2 * PI], [PI], tol) == [False]
    assert compare("angle", PI + 2 * PI, PI, tol, plain=True) is None
    # a boolean where a number is due, a ragged value, a whole number beyond the floats
    assert accepted("number", [True, 1.0], [1.0, 1.0], tol) == [False, False]
    assert accepted("array", [[1.0], [[1.0], 2.0]], [[1.0], [1.0, 2.0]], tol) == [True, False]
    # references of different shapes are stacked apart
    assert accepted("array", [[1.0], [1.0, 2.0]], [[1.0], [1.0, 2.0]], tol) == [True, True]
    assert accepted("integer", [10**400], [1], tol) == [False]
    # a scalar where an array is due
    assert accepted("array", [1.0], [[1.0]], tol) == [False]
