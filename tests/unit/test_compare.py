"""The array comparison's fast paths (slamcourse.grading.returns): a short vector compared in
Python, an expected value converted once per batch (``want_array``), decide exactly as the
general numpy rule does, on every kind of entry a learner can return."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from slamcourse.grading.returns import Tolerance, _close_arrays, compare, numeric_array

TOL = Tolerance(rtol=1e-6, atol=1e-9)
entry = st.one_of(
    st.floats(-1e6, 1e6),
    st.sampled_from([math.nan, math.inf, -math.inf, 0.0, -0.0, 1e300]),
    st.integers(-(10**6), 10**6),
    st.integers(10**308, 10**310),  # beyond floats
    st.booleans(),
)


def rule(got: object, want: object) -> bool:
    """The rule itself, written plainly: same shape, numbers only (no booleans), all finite,
    every entry within atol + rtol·|want|."""
    g, w = np.asarray(got, dtype=object), np.asarray(want, dtype=object)
    if g.shape != w.shape:
        return False
    pairs = list(zip(g.reshape(-1), w.reshape(-1), strict=True))
    for a, b in pairs:
        if type(a) not in (int, float) or type(b) not in (int, float):
            return False
        try:
            a, b = float(a), float(b)
        except OverflowError:
            return False
        if not (math.isfinite(a) and math.isfinite(b)) or abs(a - b) > TOL.atol + TOL.rtol * abs(b):
            return False
    return True


@given(
    st.lists(st.floats(-1e6, 1e6), min_size=0, max_size=20),
    st.lists(entry, min_size=0, max_size=20),
    st.lists(st.floats(-1e-6, 1e-6), min_size=20, max_size=20),
)
def test_a_vector_is_judged_by_the_rule_on_every_path(
    want: list, mixed: list, jitter: list
) -> None:
    near = [w + j for w, j in zip(want, jitter, strict=False)]
    for got in (near, mixed, mixed[: len(want)], [round(w) for w in want]):
        expected = rule(got, want)
        assert _close_arrays(got, want, TOL) is expected, (got, want)
        assert _close_arrays(got, want, TOL, numeric_array(want)) is expected, (got, want)


@given(st.integers(1, 30), st.integers(1, 4), st.data())
def test_a_matrix_with_its_expected_array_kept_is_judged_alike(
    rows: int, cols: int, data: st.DataObject
) -> None:
    want = data.draw(st.lists(st.lists(st.floats(-100, 100), min_size=cols, max_size=cols),
                              min_size=rows, max_size=rows))  # fmt: skip
    got = [[v + data.draw(st.sampled_from([0.0, 1e-12, 1e-3])) for v in row] for row in want]
    if data.draw(st.booleans()):
        got[0][0] = data.draw(entry)
    kept = numeric_array(want)
    assert kept is not None and kept.shape == (rows, cols)
    assert _close_arrays(got, want, TOL, kept) is rule(got, want)
    assert (compare("array", got, want, TOL, plain=True, want_array=kept) is None) is (
        compare("array", got, want, TOL, plain=True) is None
    )


def test_numeric_array_is_only_for_rectangular_numbers() -> None:
    assert numeric_array([[1, 2.5], [3, 4]]).dtype == float
    for value in ([], [[1], [2, 3]], [True, 1.0], [[1.0], "a"], 3.0, [[]]):
        assert numeric_array(value) is None or numeric_array(value).size == 0, value


def test_a_whole_number_beyond_the_floats_is_a_verdict_not_a_crash() -> None:
    huge = 10**400
    for spec, got, want in (("array", [1.0, huge], [1.0, 2.0]), ("number", huge, 2.0)):
        found = compare(spec, got, want, TOL, plain=True)
        assert found is not None and "too large for a float" in found.message
