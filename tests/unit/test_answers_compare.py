"""Tests of numeric comparison and formatting (slamcourse.answers.compare)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from slamcourse.answers import (
    EntryComparison,
    angle_is_close,
    compare_entries,
    format_number,
    format_window,
    is_close,
    tolerance_window,
    wrap_angle,
)
from slamcourse.errors import GraderError

moderate = st.floats(-1e12, 1e12, allow_nan=False)
tolerances = st.floats(0, 0.5, allow_nan=False)
abs_tolerances = st.floats(0, 10, allow_nan=False)

# --------------------------------------------------------------------------------------------
# Windows and is_close
# --------------------------------------------------------------------------------------------


def test_tolerance_window() -> None:
    assert tolerance_window(10.0, 0.01, 0.0) == pytest.approx((9.9, 10.1))
    assert tolerance_window(-10.0, 0.01, 0.5) == pytest.approx((-10.6, -9.4))
    assert tolerance_window(0.0, 0.5, 1e-9) == (-1e-9, 1e-9)


def test_is_close_basics() -> None:
    assert is_close(0.1419, 0.14189, 0.01, 1e-9)
    assert not is_close(0.2, 0.14189, 0.01, 1e-9)
    assert is_close(-3.0, -3.0, 0.0, 0.0)
    assert not is_close(math.nan, 1.0, 0.5, 1.0)
    assert not is_close(math.inf, 1e308, 0.5, 1.0)
    assert not is_close(1.0, math.nan, 0.5, 1.0)


@settings(max_examples=300, deadline=None)
@given(expected=moderate, rtol=tolerances, atol=abs_tolerances)
def test_is_close_accepts_edges_and_rejects_just_outside(
    expected: float, rtol: float, atol: float
) -> None:
    lo, hi = tolerance_window(expected, rtol, atol)
    assert lo <= expected <= hi
    assert is_close(lo, expected, rtol, atol)
    assert is_close(hi, expected, rtol, atol)
    assert is_close(expected, expected, rtol, atol)
    assert not is_close(math.nextafter(lo, -math.inf), expected, rtol, atol)
    assert not is_close(math.nextafter(hi, math.inf), expected, rtol, atol)


@settings(max_examples=200, deadline=None)
@given(got=moderate, expected=moderate, rtol=tolerances, atol=abs_tolerances)
def test_is_close_matches_the_formula(
    got: float, expected: float, rtol: float, atol: float
) -> None:
    tol = atol + rtol * abs(expected)
    difference = abs(got - expected)
    assume(abs(difference - tol) > 1e-9 * max(1.0, tol))  # away from rounding at the edge
    assert is_close(got, expected, rtol, atol) == (difference <= tol)


# --------------------------------------------------------------------------------------------
# Angles
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("x", "wrapped"),
    [
        (0.0, 0.0),
        (math.pi, math.pi),
        (-math.pi, math.pi),
        (3 * math.pi, math.pi),
        (3 * math.pi / 2, -math.pi / 2),
        (-3 * math.pi / 2, math.pi / 2),
        (2 * math.pi, 0.0),
        (7.0, 7.0 - 2 * math.pi),
    ],
)
def test_wrap_angle_values(x: float, wrapped: float) -> None:
    assert wrap_angle(x) == pytest.approx(wrapped, abs=1e-12)


def test_wrap_angle_non_finite() -> None:
    assert math.isnan(wrap_angle(math.inf))
    assert math.isnan(wrap_angle(math.nan))


@settings(max_examples=400, deadline=None)
@given(x=st.floats(-1e9, 1e9, allow_nan=False))
def test_wrap_angle_range_and_multiple_of_two_pi(x: float) -> None:
    w = wrap_angle(x)
    assert -math.pi < w <= math.pi
    turns = (x - w) / math.tau
    assert abs(turns - round(turns)) <= 1e-9 * max(1.0, abs(turns))


def test_angle_is_close() -> None:
    assert angle_is_close(-math.pi / 2, 3 * math.pi / 2, 0.01, 1e-9)
    assert angle_is_close(math.pi - 1e-4, -math.pi + 1e-4, 0.0, 1e-3)
    assert angle_is_close(0.7854 + 2 * math.pi, math.pi / 4, 0.01, 0)
    assert not angle_is_close(math.pi / 2, -math.pi / 2, 0.01, 1e-9)
    assert not angle_is_close(math.nan, 0.0, 0.1, 0.1)
    # tolerance uses the wrapped reference: 2π·k + 0.1 is as strict as 0.1
    assert not angle_is_close(0.102 + 4 * math.pi, 0.1 + 4 * math.pi, 0.01, 0.0)
    assert angle_is_close(0.1005 + 4 * math.pi, 0.1 + 4 * math.pi, 0.01, 0.0)


@settings(max_examples=200, deadline=None)
@given(
    expected=st.floats(-100, 100, allow_nan=False),
    turns=st.integers(-50, 50),
    rtol=tolerances,
    atol=st.floats(1e-6, 1, allow_nan=False),
)
def test_angles_equal_modulo_two_pi(expected: float, turns: int, rtol: float, atol: float) -> None:
    assert angle_is_close(expected + turns * math.tau, expected, rtol, atol)


# --------------------------------------------------------------------------------------------
# compare_entries
# --------------------------------------------------------------------------------------------


def test_compare_vectors() -> None:
    result = compare_entries([0.3, -0.09, 5.0], [0.3, -0.1, 5.0], 0.01, 1e-9)
    assert isinstance(result, EntryComparison)
    assert result.shape_ok and not result.ok
    assert result.got_shape == result.expected_shape == (3,)
    assert result.wrong == [(1,)]
    assert compare_entries([0.3, -0.1], (0.3, -0.1), 0.01, 0).ok


def test_compare_matrices() -> None:
    result = compare_entries([[1, 2], [3, 4.5]], [[1, 2.5], [3, 4]], 0.01, 0)
    assert result.wrong == [(0, 1), (1, 1)]
    assert result.got_shape == (2, 2)
    assert compare_entries([[1, 2], [3, 4]], [[1, 2], [3, 4]], 0, 0).ok


def test_compare_shape_mismatch() -> None:
    result = compare_entries([1, 2], [[1, 2]], 0.01, 0)
    assert not result.shape_ok and not result.ok
    assert result.got_shape == (2,) and result.expected_shape == (1, 2)
    assert result.wrong == []
    assert not compare_entries([1, 2, 3], [1, 2], 0.01, 0).shape_ok
    assert not compare_entries([[1, 2, 3]], [[1, 2], [3, 4]], 0.01, 0).shape_ok


def test_compare_accepts_numpy_arrays() -> None:
    expected = np.array([[1.0, 2.0], [3.0, 4.0]])
    assert compare_entries([[1, 2], [3, 4]], expected, 0.01, 0).ok
    assert compare_entries(np.array([1.0, 2.0]), [np.float64(1), np.float64(2)], 0, 0).ok


def test_compare_angles() -> None:
    got = [3 * math.pi / 2, 1.0 + 2 * math.pi]
    expected = [-math.pi / 2, 1.0]
    assert compare_entries(got, expected, 0.01, 1e-9, angle=True).ok
    assert compare_entries(got, expected, 0.01, 1e-9, angle=[0]).wrong == [(1,)]
    assert compare_entries(got, expected, 0.01, 1e-9, angle=False).wrong == [(0,), (1,)]
    pose = compare_entries([[0, 0, 2 * math.pi]], [[0, 0, 0]], 0, 1e-9, angle={2})
    assert pose.ok


def test_compare_exact() -> None:
    assert compare_entries([3, 4], [3, 4], 0.5, 0.5, exact=True).ok
    assert compare_entries([3, 4.0001], [3, 4], 0.5, 0.5, exact=True).wrong == [(1,)]
    assert compare_entries([math.pi], [-math.pi], 0, 0, exact=True, angle=True).ok


def test_compare_non_finite_answer_is_wrong() -> None:
    assert compare_entries([math.nan, math.inf], [1, 2], 1, 1).wrong == [(0,), (1,)]


def test_compare_grader_errors() -> None:
    with pytest.raises(GraderError, match="different lengths"):
        compare_entries([[1, 2], [3]], [[1, 2], [3]], 0, 0)
    with pytest.raises(GraderError, match="outside"):
        compare_entries([1, 2], [1, 2], 0, 0, angle=[2])
    with pytest.raises(GraderError, match="not a number"):
        compare_entries(["a"], [1], 0, 0)
    with pytest.raises(GraderError, match="more than two"):
        compare_entries([[[1]]], [[[1]]], 0, 0)


@settings(max_examples=100, deadline=None)
@given(
    values=st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=1, max_size=6),
    data=st.data(),
)
def test_compare_finds_exactly_the_perturbed_entries(
    values: list[float], data: st.DataObject
) -> None:
    bad = data.draw(st.sets(st.integers(0, len(values) - 1)))
    got = [v + (1.0 + abs(v)) if i in bad else v for i, v in enumerate(values)]
    result = compare_entries(got, values, 0.01, 1e-9)
    assert result.wrong == [(i,) for i in sorted(bad)]
    assert result.ok == (not bad)


# --------------------------------------------------------------------------------------------
# Formatting
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("x", "text"),
    [
        (10609.0, "10609"),
        (0.14189, "0.1419"),
        (5.0, "5"),
        (-0.09, "-0.09"),
        (1.42e-05, "1.42e-05"),
        (1.41899e-05, "1.419e-05"),
        (2.5, "2.5"),
        (12.345678, "12.3457"),
        (-3.000001, "-3"),
        (0.0, "0"),
        (-0.0, "0"),
        (0.25, "0.25"),
        (1e20, "1e+20"),
        (math.inf, "inf"),
        (-math.inf, "-inf"),
        (math.nan, "nan"),
        (-7, "-7"),
    ],
)
def test_format_number(x: float, text: str) -> None:
    assert format_number(x) == text


@settings(max_examples=200, deadline=None)
@given(x=st.floats(-1e300, 1e300))
def test_format_number_is_close_to_the_value(x: float) -> None:
    text = format_number(x)
    assert float(text) == pytest.approx(x, rel=1e-3, abs=1e-4)


def test_format_window() -> None:
    assert format_window(9.9, 10.1) == "[9.9, 10.1]"
    assert format_window(*tolerance_window(0.1419, 1e-4, 0)) == "[0.14189, 0.14191]"
    assert format_window(2.0, 2.0) == "[2, 2]"


@settings(max_examples=200, deadline=None)
@given(expected=st.floats(-1e6, 1e6, allow_nan=False), rtol=st.floats(1e-9, 0.1))
def test_format_window_tells_ends_apart(expected: float, rtol: float) -> None:
    lo, hi = tolerance_window(expected, rtol, 1e-9)
    text = format_window(lo, hi)
    a, b = text[1:-1].split(", ")
    assert a != b
