"""Feedback never prints two different numbers alike, and shows inputs exactly."""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from slamcourse.course.model import Tolerance
from slamcourse.grading.returns import compare, show, show_exact, show_pair

finite = st.floats(allow_nan=False, allow_infinity=False)


@given(finite, finite)
def test_two_different_numbers_never_print_alike(a: float, b: float) -> None:
    want, got = show_pair(a, b)
    assert (want == got) == (a == b)


@given(st.lists(finite, min_size=1, max_size=4), st.integers(0, 3), finite)
def test_two_different_vectors_never_print_alike(values: list[float], i: int, x: float) -> None:
    other = list(values)
    other[i % len(values)] = x
    want, got = show_pair(values, other)
    assert (want == got) == (values == other)


def test_the_issues_example_gets_its_digits() -> None:
    assert show(-0.0069841) == show(-0.0069843)  # the compact form alone hides it
    assert show_pair(-0.0069841, -0.0069843) == ("-0.0069841", "-0.0069843")
    message = compare("number", -0.0069843, -0.0069841, Tolerance(rtol=1e-6, atol=1e-9))
    assert message is not None and "-0.0069841" in message.message


def test_inputs_are_shown_as_they_must_be_typed() -> None:
    assert show_exact(math.pi) == "3.141592653589793"
    assert show_exact(math.nextafter(math.pi, 0)) == "3.1415926535897927"
    assert show_exact((1, 2, 3.5)) == "(1, 2, 3.5)"
    assert show_exact([1.0, 2]) == "[1.0, 2]"
    assert show_exact("a\n") == "'a\\n'"


@given(finite)
def test_exact_floats_round_trip(x: float) -> None:
    assert float(show_exact(x)) == x
