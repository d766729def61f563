"""Tests of learner answer parsing (slamcourse.answers.parse)."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.answers import (
    parse_ids,
    parse_integer,
    parse_matrix,
    parse_number,
    parse_vector,
)
from slamcourse.errors import AnswerFormatError

PARSERS: list[Callable[[str], Any]] = [
    parse_number,
    parse_integer,
    parse_vector,
    parse_matrix,
    parse_ids,
]

finite = st.floats(allow_nan=False, allow_infinity=False)

# --------------------------------------------------------------------------------------------
# Numbers
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("42", 42.0),
        ("  -0.09\n", -0.09),
        (".5", 0.5),
        ("5.", 5.0),
        ("1.5e-3", 0.0015),
        ("2E5", 2e5),
        ("7/5", 1.4),
        ("pi/4", math.pi / 4),
        ("sqrt(2)/2", math.sqrt(2) / 2),
        ("√2/2", math.sqrt(2) / 2),
        ("2π", 2 * math.pi),
        ("−1", -1.0),
        ("–0.5", -0.5),
        ("1 - 0.5", 0.5),
        ("pi / 4", math.pi / 4),
        ("atan2(1, 1)", math.pi / 4),
        ("-(3)", -3.0),
    ],
)
def test_parse_number_forms(text: str, value: float) -> None:
    assert parse_number(text) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "empty answer — expected a number such as 0.25"),
        ("   ", "empty answer"),
        ("0.3 -0.09", "expected one number, got 2 — give a single value"),
        ("1 2 3", "expected one number, got 3"),
        ("1, 2", "expected one number, got 2"),
        ("2 pi", "for a product write '*'"),
        ("45°", "angles are in radians"),
        ("45 °", "pi/4 or 0.785"),
        ("45 deg", "angles are in radians"),
        ("90 degrees", "angles are in radians"),
        ("5 m", "write the number without its unit: 5, not 5 m"),
        ("5m", "write the number without its unit"),
        ("3.2 m/s", "without its unit: 3.2, not 3.2 m/s"),
        ("pi/4 rad", "without its unit"),
        ("0,5", "use a point as the decimal separator"),
        ("-12,75", "decimal separator"),
        ("nan", "'nan' and 'inf' are not answers"),
        ("-inf", "'nan' and 'inf'"),
        ("Infinity", "'nan' and 'inf'"),
        ("∞", "'nan' and 'inf'"),
        ("1e400", "too large"),
        ("1e308*10", "not a finite number"),
        ("1/0", "division by zero — expected a number such as"),
        ("x", "unknown name 'x'; you can use pi, e, tau"),
        ("(1 + 2", "never closed"),
        ("5,", "trailing ','"),
        ("x = 3", "not an equation"),
    ],
)
def test_parse_number_messages(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        parse_number(text)


def test_parse_number_keeps_scientific_notation_and_e() -> None:
    assert parse_number("1e5") == 1e5
    assert parse_number("1e-05") == 1e-05
    assert parse_number("2e") == pytest.approx(2 * math.e)


@settings(max_examples=300, deadline=None)
@given(x=finite)
def test_parse_number_round_trips_repr(x: float) -> None:
    assert parse_number(repr(x)) == x
    assert parse_number(f" {x!r} ") == x


@settings(max_examples=200, deadline=None)
@given(
    a=st.integers(-(10**9), 10**9),
    b=st.integers(-(10**9), 10**9).filter(lambda b: b != 0),
)
def test_parse_number_fractions(a: int, b: int) -> None:
    assert parse_number(f"{a}/{b}") == a / b


@pytest.mark.parametrize(("text", "value"), [("9", 9), ("9.0", 9), ("1e3", 1000), ("-18/2", -9)])
def test_parse_integer(text: str, value: int) -> None:
    result = parse_integer(text)
    assert result == value
    assert isinstance(result, int)


def test_parse_integer_tolerates_rounding_noise() -> None:
    assert parse_integer("0.1*30") == 3


@pytest.mark.parametrize(
    ("text", "message"),
    [("9.5", "expected a whole number such as 9, got 9.5"), ("", "empty answer"), ("9 m", "unit")],
)
def test_parse_integer_messages(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        parse_integer(text)


@settings(max_examples=100, deadline=None)
@given(n=st.integers(-(10**12), 10**12))
def test_parse_integer_round_trips(n: int) -> None:
    assert parse_integer(str(n)) == n
    assert parse_integer(f"{n}.0") == n


# --------------------------------------------------------------------------------------------
# Vectors
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    [
        "[0.3, -0.09]",
        "(0.3, -0.09)",
        "0.3, -0.09",
        "0.3 -0.09",
        "[0.3 -0.09]",
        "[ 0.3  -0.09 ]",
        "0.3; -0.09",
        "[0.3,-0.09]",
        "[0.3, −0.09]",
        "[0.3, -0.09,]",
        "[0.3\n -0.09]",
        "[3/10, -9/100]",
    ],
)
def test_parse_vector_forms(text: str) -> None:
    assert parse_vector(text) == pytest.approx([0.3, -0.09], rel=1e-15)


def test_parse_vector_entries_may_be_formulas() -> None:
    got = parse_vector("[pi/4, -sqrt(2), atan2(1, 1), 2π]")
    assert got == pytest.approx([math.pi / 4, -math.sqrt(2), math.pi / 4, 2 * math.pi])
    assert parse_vector("pi / 4  1") == pytest.approx([math.pi / 4, 1.0])
    assert parse_vector("2 * -1 3") == [-2.0, 3.0]
    assert parse_vector("[5]") == [5.0]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "empty answer — expected a vector such as [0.3, -0.09]"),
        ("[]", "the vector is empty"),
        ("[0.3 - 0.09]", "a sign stands apart from its number in '0.3 - 0.09'"),
        ("- 0.3 0.5", "a sign stands apart"),
        ("0.3 + 0.1 2", "a sign stands apart"),
        ("[[1, 2], [3, 4]]", "expected a vector; this looks like a matrix"),
        ("[1 2; 3 4]", "this looks like a matrix"),
        ("[1, 2; 3, 4]", "this looks like a matrix"),
        ("((1, 2), (3, 4))", "a bracketed list inside a list"),
        ("[1, 2] 3", "brackets must enclose the whole vector"),
        ("[1,,2]", "entry 2 is empty"),
        ("[1, x]", "entry 2 ('x'): unknown name 'x'"),
        ("[1, 45°]", "entry 2 ('45°'): angles are in radians"),
        ("[1 m, 2 m]", "entry 1 ('1 m'): write the number without its unit"),
        ("[0.3 -0.09, 1]", "entry 1 ('0.3 -0.09'): holds 2 numbers"),
        ("[1, 2", "never closed"),
        ("[1, 2)", "mismatched brackets"),
        ("[1, nan]", "'nan' and 'inf'"),
    ],
)
def test_parse_vector_messages(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        parse_vector(text)


VECTOR_STYLES: list[Callable[[list[str]], str]] = [
    lambda xs: "[" + ", ".join(xs) + "]",
    lambda xs: "(" + ", ".join(xs) + ")",
    lambda xs: ", ".join(xs),
    lambda xs: " ".join(xs),
    lambda xs: "[" + "  ".join(xs) + "]",
    lambda xs: "; ".join(xs),
    lambda xs: "[" + ",".join(xs) + ",]",
    lambda xs: "[" + "\n ".join(xs) + "]",
]


@settings(max_examples=200, deadline=None)
@given(
    values=st.lists(finite, min_size=1, max_size=6),
    style=st.sampled_from(range(len(VECTOR_STYLES))),
)
def test_parse_vector_round_trips(values: list[float], style: int) -> None:
    text = VECTOR_STYLES[style]([repr(v) for v in values])
    assert parse_vector(text) == values


# --------------------------------------------------------------------------------------------
# Matrices
# --------------------------------------------------------------------------------------------

M = [[1.0, 2.0], [3.0, -4.0]]


@pytest.mark.parametrize(
    "text",
    [
        "[[1, 2], [3, -4]]",
        "[[1,2],[3,-4]]",
        "[[1. 2.]\n [3. -4.]]",
        "[[1 2] [3 -4]]",
        "((1, 2), (3, -4))",
        "[1, 2], [3, -4]",
        "[1 2; 3 -4]",
        "[1, 2; 3, -4]",
        "1 2; 3 -4",
        "1 2\n3 -4",
        "1, 2\n3, -4\n",
        "[1 2\n 3 -4]",
        "[1 2; 3 -4;]",
        "[[1, 2],\n [3, −4]]",
        "[[sqrt(1), 4/2], [3, -2^2]]",
    ],
)
def test_parse_matrix_forms(text: str) -> None:
    assert parse_matrix(text) == M


def test_parse_matrix_single_row_and_column() -> None:
    assert parse_matrix("[[1, 2, 3]]") == [[1.0, 2.0, 3.0]]
    assert parse_matrix("[1; 2; 3]") == [[1.0], [2.0], [3.0]]
    assert parse_matrix("[[5]]") == [[5.0]]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "empty answer — expected a matrix such as [[1, 2], [3, 4]]"),
        ("[[1, 2], [3]]", "rows have different lengths (2, 1)"),
        ("[1 2 3; 4 5]", "rows have different lengths (3, 2)"),
        ("[1, 2, 3]", "this looks like a flat list — write each row in its own brackets"),
        ("5", "flat list"),
        ("[[1, 2], 3]", "every row of a matrix must be in its own brackets"),
        ("[[[1]]]", "row 1 has brackets inside it"),
        ("[[]]", "row 1 is empty"),
        ("[[1, x], [3, 4]]", "row 1, entry 2 ('x'): unknown name 'x'"),
        ("[[1, 2], [3, 4 m]]", "row 2, entry 2 ('4 m'): write the number without its unit"),
        ("[[1, 2], [3, 4]", "never closed"),
        ("[1 - 2; 3 4]", "a sign stands apart"),
    ],
)
def test_parse_matrix_messages(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        parse_matrix(text)


def _rows(matrix: list[list[float]], sep: str) -> list[str]:
    return [sep.join(repr(v) for v in row) for row in matrix]


MATRIX_STYLES: list[Callable[[list[list[float]]], str]] = [
    lambda m: "[" + ", ".join("[" + r + "]" for r in _rows(m, ", ")) + "]",
    lambda m: "[" + "\n ".join("[" + r + "]" for r in _rows(m, " ")) + "]",
    lambda m: "(" + ", ".join("(" + r + ",)" for r in _rows(m, ", ")) + ")",
    lambda m: "[" + "; ".join(_rows(m, " ")) + "]",
    lambda m: "\n".join(_rows(m, "  ")),
    lambda m: "; ".join(_rows(m, ", ")),
]


@settings(max_examples=150, deadline=None)
@given(
    shape=st.tuples(st.integers(2, 4), st.integers(1, 4)),
    data=st.data(),
    style=st.sampled_from(range(len(MATRIX_STYLES))),
)
def test_parse_matrix_round_trips(shape: tuple[int, int], data: st.DataObject, style: int) -> None:
    rows, cols = shape
    matrix = data.draw(
        st.lists(st.lists(finite, min_size=cols, max_size=cols), min_size=rows, max_size=rows)
    )
    assert parse_matrix(MATRIX_STYLES[style](matrix)) == matrix


# --------------------------------------------------------------------------------------------
# Choice ids
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "ids"),
    [
        ("a", ["a"]),
        ("a c", ["a", "c"]),
        ("a,c", ["a", "c"]),
        ("A, C", ["a", "c"]),
        ("c a b", ["c", "a", "b"]),
        ("[c, a, b]", ["c", "a", "b"]),
        ("a) c)", ["a", "c"]),
        ("step-1 step_2", ["step-1", "step_2"]),
        ("a a", ["a", "a"]),
    ],
)
def test_parse_ids(text: str, ids: list[str]) -> None:
    assert parse_ids(text) == ids


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "empty answer — expected choice ids"),
        (" , ; ", "empty answer"),
        ("a!", "'a!' is not a choice id"),
        ("é", "is not a choice id"),
    ],
)
def test_parse_ids_messages(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        parse_ids(text)


# --------------------------------------------------------------------------------------------
# Any text: only AnswerFormatError, never anything else
# --------------------------------------------------------------------------------------------

ANSWER_CHARS = "0123456789.eE+-*/^() ,;[]{}\n\t−–°%πτ√²pisqrtnafmdgx'\"#_"


@pytest.mark.parametrize("parser", PARSERS, ids=lambda p: p.__name__)
@settings(max_examples=200, deadline=None)
@given(text=st.text(max_size=80))
def test_any_text_gives_a_value_or_answer_format_error(
    parser: Callable[[str], Any], text: str
) -> None:
    try:
        parser(text)
    except AnswerFormatError as err:
        assert str(err)


@pytest.mark.parametrize("parser", PARSERS, ids=lambda p: p.__name__)
@settings(max_examples=300, deadline=None)
@given(text=st.text(alphabet=ANSWER_CHARS, max_size=40))
def test_answer_like_text_gives_a_value_or_answer_format_error(
    parser: Callable[[str], Any], text: str
) -> None:
    try:
        value = parser(text)
    except AnswerFormatError as err:
        assert str(err)
        return
    if parser is parse_number:
        assert math.isfinite(value)
    elif parser is parse_vector:
        assert value and all(math.isfinite(v) for v in value)
    elif parser is parse_matrix:
        assert value and len({len(row) for row in value}) == 1


@pytest.mark.parametrize("parser", PARSERS, ids=lambda p: p.__name__)
def test_huge_and_nasty_inputs(parser: Callable[[str], Any]) -> None:
    nasty = ["1" * 5000, "[" * 2000 + "]" * 2000, "(" * 500, "-" * 999 + "1", "\x00"]
    if parser is not parse_ids:
        nasty.append("1e999")
    for text in nasty:
        with pytest.raises(AnswerFormatError):
            parser(text)
