"""Tests of the safe formula evaluator (slamcourse.answers.expr)."""

from __future__ import annotations

import contextlib
import math
import re
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.answers import Expression, compile_expression, evaluate_number
from slamcourse.answers.expr import FUNCTIONS, preprocess
from slamcourse.errors import AnswerFormatError, GraderError

# --------------------------------------------------------------------------------------------
# Preprocessing
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "python"),
    [
        ("2pi", "2*pi"),
        ("2π", "2*pi"),
        ("2(x+1)", "2*(x+1)"),
        ("3sqrt(2)", "3*sqrt(2)"),
        ("1e-3", "1e-3"),
        ("2E5", "2E5"),
        ("1.5e+2x", "1.5e+2*x"),
        ("2e", "2*e"),
        ("x2", "x2"),
        ("2x2", "2*x2"),
        ("2 pi", "2 pi"),
        ("x(1+y)", "x(1+y)"),
        ("2^3", "2**3"),
        ("x²+y³", "x**2+y**3"),
        ("a−b–c", "a-b-c"),
        ("a×b·c⋅d÷e", "a*b*c*d/e"),
        ("√2", "sqrt(2)"),
        ("√x", "sqrt(x)"),
        ("√(x+1)", "sqrt(x+1)"),
        ("√sin(x)", "sqrt(sin(x))"),
        ("√√16", "sqrt(sqrt(16))"),
        ("2√2", "2*sqrt(2)"),
        ("√π", "sqrt(pi)"),
        ("τ/2", "tau/2"),
        ("aπ", "a pi"),
        ("1\n+\t2", "1 + 2"),
    ],
)
def test_preprocess(text: str, python: str) -> None:
    assert preprocess(text) == python


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("2pi", 2 * math.pi),
        ("2(3+1)", 8.0),
        ("3sqrt(4)", 6.0),
        ("1e-3", 0.001),
        ("2E5", 200000.0),
        ("2e", 2 * math.e),
        ("−1", -1.0),
        ("2×3", 6.0),
        ("6÷4", 1.5),
        ("2^3^2", 512.0),
        ("-2**2", -4.0),
        ("√2/2", math.sqrt(2) / 2),
        ("3²", 9.0),
        ("2³", 8.0),
        ("τ", math.tau),
        ("7/5", 1.4),
        ("+3", 3.0),
        ("10", 10.0),
    ],
)
def test_evaluate_number_forms(text: str, value: float) -> None:
    result = evaluate_number(text)
    assert isinstance(result, float)
    assert result == pytest.approx(value, rel=1e-15)


def test_sqrt_needs_an_operand() -> None:
    with pytest.raises(AnswerFormatError, match="√2"):
        compile_expression("√-2")
    with pytest.raises(AnswerFormatError, match="√"):
        compile_expression("2*√")


# --------------------------------------------------------------------------------------------
# Functions, names, the Expression object
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("sqrt(16)", 4.0),
        ("exp(0)", 1.0),
        ("log(e)", 1.0),
        ("log(8, 2)", 3.0),
        ("log10(1000)", 3.0),
        ("sin(pi/2)", 1.0),
        ("cos(0)", 1.0),
        ("tan(0)", 0.0),
        ("asin(1)", math.pi / 2),
        ("acos(1)", 0.0),
        ("atan(1)", math.pi / 4),
        ("atan2(1, -1)", 3 * math.pi / 4),
        ("hypot(3, 4)", 5.0),
        ("abs(-2.5)", 2.5),
        ("floor(-2.5)", -3.0),
        ("ceil(2.1)", 3.0),
        ("min(3, 1, 2)", 1.0),
        ("max(3, 1)", 3.0),
    ],
)
def test_functions(text: str, value: float) -> None:
    assert evaluate_number(text) == pytest.approx(value, abs=1e-12)


def test_every_function_is_covered() -> None:
    assert set(FUNCTIONS) == {
        "sqrt", "exp", "log", "log10", "sin", "cos", "tan", "asin", "acos", "atan",
        "atan2", "hypot", "abs", "floor", "ceil", "min", "max",
    }  # fmt: skip


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("atan2(1)", "atan2 takes 2 arguments, got 1"),
        ("hypot(1, 2, 3)", "hypot takes 2 arguments"),
        ("log(1, 2, 3)", "log takes 1 or 2 arguments"),
        ("min(1)", "min takes at least 2 arguments"),
        ("sqrt()", "sqrt takes 1 argument, got 0"),
        ("sqrt(x=1)", "named argument"),
        ("sqrt", "'sqrt' is a function; write sqrt(…)"),
        ("foo(1)", "unknown function 'foo'"),
        ("sqr(2)", "did you mean 'sqrt'"),
        ("Pi", "did you mean 'pi'"),
    ],
)
def test_call_errors(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        compile_expression(text)


def test_unknown_name_lists_what_can_be_used() -> None:
    with pytest.raises(AnswerFormatError) as info:
        compile_expression("x + dx", ["dx", "dy", "q"])
    assert "unknown name 'x'" in str(info.value)
    assert "dx, dy, q, pi, e, tau" in str(info.value)


def test_variable_called_like_a_function() -> None:
    with pytest.raises(AnswerFormatError, match=r"'q' is not a function; write q\*\(…\)"):
        compile_expression("q(1+q)", ["q"])


def test_expression_object() -> None:
    ex = compile_expression("-dx/sqrt(q)", ["dx", "dy", "q"])
    assert isinstance(ex, Expression)
    assert ex.text == "-dx/sqrt(q)"
    assert ex.names == frozenset({"dx", "q"})
    assert not ex.is_condition
    assert ex.evaluate({"dx": 3, "q": 4.0, "dy": 100}) == -1.5


def test_variables_shadow_constants() -> None:
    ex = compile_expression("e + pi", ["e"])
    assert ex.names == frozenset({"e"})
    assert ex.evaluate({"e": 1.0}) == pytest.approx(1 + math.pi)


def test_missing_value_is_a_grader_error() -> None:
    with pytest.raises(GraderError, match="'x'"):
        compile_expression("x + 1", ["x"]).evaluate({})


def test_unknown_backend() -> None:
    with pytest.raises(GraderError, match="backend"):
        compile_expression("1").evaluate({}, backend="torch")


# --------------------------------------------------------------------------------------------
# Rejections
# --------------------------------------------------------------------------------------------

MALICIOUS = [
    "__import__('os')",
    "__import__(os)",
    "().__class__",
    "x.__class__",
    "'a'*9",
    '"a"',
    "b'a'",
    "[x for x in y]",
    "(x for x in y)",
    "lambda: 1",
    "import os",
    "exec('1')",
    "eval(x)",
    "open(x)",
    "getattr(x, y)",
    "x[0]",
    "{1: 2}",
    "{1}",
    "[1, 2]",
    "(1, 2)",
    "1 if x else 2",
    "(y := 1)",
    "*x",
    "1j",
    "0x10",
    "1_000",
    "True",
    "None",
    "...",
    "x @ y",
    "x // y",
    "x % y",
    "x << 2",
    "~x",
    "x & y",
    "1 # comment",
    "1; 2",
    "a\\\n+1",
    "f'{x}'",
    "x\x00",
    "((((" * 30 + "1" + "))))" * 30,
    "-" * 999 + "1",
    "+".join(["1"] * 400),
    "not " * 200 + "1",
    "sqrt(" * 60 + "1" + ")" * 60,
    "√" * 500 + "2",
    "1" * 31,
    "1e400",
    "9" * 1001,
]


@pytest.mark.parametrize("text", MALICIOUS)
def test_malicious_inputs_are_rejected_quickly(text: str) -> None:
    start = time.perf_counter()
    for logic in (False, True):
        with pytest.raises(AnswerFormatError):
            compile_expression(text, ["x", "y"], logic=logic)
    assert time.perf_counter() - start < 0.5


def test_power_tower_fails_cleanly() -> None:
    start = time.perf_counter()
    ex = compile_expression("10**10**10")
    with pytest.raises(AnswerFormatError, match="too large"):
        ex.evaluate({})
    with pytest.raises(AnswerFormatError, match="too large"):
        evaluate_number("9^9^9^9")
    assert np.isinf(ex.evaluate({}, backend="numpy"))
    assert time.perf_counter() - start < 0.5


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("import os", "'import' is not allowed"),
        ("2^3 + lambda: 1", "':' cannot be used"),
        ("x = 5", "not an equation"),
        ("2*", "ends with '*'"),
        ("2 3", "next to each other"),
        ("(1 + 2", "never closed"),
        ("1 + 2)", "no matching"),
        ("x[0]", "round brackets"),
        ("().__class__", "attribute access"),
        ("x < 1", "comparison is not allowed"),
        ("1 and 2", "'and' is not allowed"),
        ("1" * 31, "too long (at most 30 characters)"),
        ("1e400", "'1e400' is too large"),
        ("x" * 1001, "at most 1000"),
        ("((" * 25 + "1" + "))" * 25, "nested too deeply"),
        ("+".join(["x"] * 200), "more than 300 parts"),
        ("+".join(["x"] * 45), "nested too deeply"),
        ("", "empty formula"),
        ("   ", "empty formula"),
    ],
)
def test_rejection_messages(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=re.escape(message)):
        compile_expression(text, ["x"])


def test_limits_allow_reasonable_formulas() -> None:
    assert evaluate_number("+".join(["1"] * 39)) == 39.0
    assert evaluate_number("(" * 39 + "2" + ")" * 39) == 2.0
    assert evaluate_number("1" * 30) == float("1" * 30)


# --------------------------------------------------------------------------------------------
# Math errors (math backend)
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("1/0", "division by zero"),
        ("sqrt(-1)", r"sqrt\(-1\) is not defined"),
        ("log(0)", r"log\(0\) is not defined"),
        ("log(8, 1)", "is not defined"),
        ("asin(2)", "is not defined"),
        ("(-8)**(1/3)", "not a real number"),
        ("0**-1", "negative power"),
        ("exp(1000)", "too large"),
        ("1e308*10", "not a finite number"),
    ],
)
def test_math_errors(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=message):
        evaluate_number(text)


def test_math_error_names_the_values() -> None:
    ex = compile_expression("-dx/sqrt(q)", ["dx", "q"])
    with pytest.raises(AnswerFormatError, match="division by zero at dx=1, q=0"):
        ex.evaluate({"dx": 1, "q": 0})


def test_negative_base_integer_power_is_fine() -> None:
    assert evaluate_number("(-2)**3") == -8.0
    assert evaluate_number("(-2)^2") == 4.0


# --------------------------------------------------------------------------------------------
# Logic (require conditions)
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "env", "expected"),
    [
        ("hypot(x, y) > 1", {"x": 1, "y": 1}, True),
        ("hypot(x, y) > 1", {"x": 0.5, "y": 0.5}, False),
        ("0 < x < 1", {"x": 0.5, "y": 0}, True),
        ("0 < x < 1", {"x": 1, "y": 0}, False),
        ("x >= 1 and y <= 2", {"x": 1, "y": 2}, True),
        ("x == 1 or y != 2", {"x": 0, "y": 2}, False),
        ("not x == 0", {"x": 0, "y": 0}, False),
        ("not (x > 1 or y > 1) and x == y", {"x": 0.5, "y": 0.5}, True),
    ],
)
def test_conditions(text: str, env: dict[str, float], expected: bool) -> None:
    ex = compile_expression(text, ["x", "y"], logic=True)
    assert ex.is_condition
    result = ex.evaluate(env)
    assert isinstance(result, bool)
    assert result is expected
    array = ex.evaluate({k: np.array([v, v]) for k, v in env.items()}, backend="numpy")
    assert array.dtype == bool
    assert array.tolist() == [expected, expected]


def test_logic_mode_still_evaluates_numbers() -> None:
    ex = compile_expression("dim + 2*n", ["dim", "n"], logic=True)
    assert not ex.is_condition
    assert ex.evaluate({"dim": 2, "n": 3}) == 8.0


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("(x > 1) + 1", "needs numbers, not a condition"),
        ("x and y", "joins conditions"),
        ("not x", "joins conditions"),
        ("sqrt(x > 1)", "needs numbers"),
        ("x in y", "'in'/'is'"),
        ("x = 1", "use '=='"),
    ],
)
def test_logic_type_errors(text: str, message: str) -> None:
    with pytest.raises(AnswerFormatError, match=message):
        compile_expression(text, ["x", "y"], logic=True)


def test_short_circuit_avoids_errors() -> None:
    ex = compile_expression("x != 0 and 1/x > 2", ["x"], logic=True)
    assert ex.evaluate({"x": 0}) is False
    assert ex.evaluate({"x": 0.25}) is True


# --------------------------------------------------------------------------------------------
# numpy backend
# --------------------------------------------------------------------------------------------


def test_numpy_matches_reference_at_random_points() -> None:
    rng = np.random.default_rng(7)
    dx, dy = rng.uniform(-5, 5, 200), rng.uniform(-5, 5, 200)
    q = dx**2 + dy**2
    ex = compile_expression("-dx/sqrt(q)", ["dx", "dy", "q"])
    got = ex.evaluate({"dx": dx, "dy": dy, "q": q}, backend="numpy")
    assert isinstance(got, np.ndarray)
    np.testing.assert_allclose(got, -dx / np.sqrt(q), rtol=1e-14)
    ex2 = compile_expression("atan2(dy, dx) - pi/2 + hypot(dx, dy)^2 / q", ["dx", "dy", "q"])
    got2 = ex2.evaluate({"dx": dx, "dy": dy, "q": q}, backend="numpy")
    np.testing.assert_allclose(got2, np.arctan2(dy, dx) - np.pi / 2 + 1, rtol=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    dx=st.floats(-1e3, 1e3, allow_nan=False),
    q=st.floats(1e-6, 1e6, allow_nan=False),
)
def test_math_and_numpy_backends_agree(dx: float, q: float) -> None:
    ex = compile_expression("-dx/sqrt(q) + min(dx, q)*log(q, 10) - 2abs(dx)^(1/2)", ["dx", "q"])
    scalar = ex.evaluate({"dx": dx, "q": q})
    reference = -dx / np.sqrt(q) + min(dx, q) * np.log10(q) - 2 * np.sqrt(abs(dx))
    assert scalar == pytest.approx(float(reference), rel=1e-9, abs=1e-9)
    vector = ex.evaluate({"dx": np.array([dx]), "q": np.array([q])}, backend="numpy")
    assert vector.tolist() == pytest.approx([scalar], rel=1e-12, abs=1e-12)


def test_numpy_errors_become_nan_and_inf() -> None:
    ex = compile_expression("1/x + sqrt(x + 1)", ["x"])
    got = ex.evaluate({"x": np.array([0.0, -2.0, 3.0])}, backend="numpy")
    assert np.isinf(got[0]) and np.isnan(got[1]) and got[2] == pytest.approx(1 / 3 + 2)


def test_numpy_broadcasts_constants_to_env_shape() -> None:
    got = compile_expression("pi/4").evaluate({"a": np.zeros((2, 3))}, backend="numpy")
    assert got.shape == (2, 3)
    assert np.all(got == math.pi / 4)
    got[0, 0] = 1.0  # writable, not a broadcast view
    partial = compile_expression("x + 1", ["x", "y"]).evaluate(
        {"x": 1.0, "y": np.arange(4.0)}, backend="numpy"
    )
    assert partial.tolist() == [2.0] * 4


def test_math_backend_does_not_import_numpy() -> None:
    code = textwrap.dedent(
        """
        import sys
        from slamcourse.answers import compile_expression, evaluate_number, parse_vector
        from slamcourse.answers import parse_matrix, compare_entries, format_number
        ex = compile_expression("-dx/sqrt(q) > 0 and x^2 < 3", ["dx", "q", "x"], logic=True)
        ex.evaluate({"dx": -1, "q": 2, "x": 1})
        evaluate_number("2pi/3")
        compare_entries(parse_vector("[1, 2]"), [1, 2], 0.01, 0)
        parse_matrix("[1 2; 3 4]")
        format_number(0.25)
        assert "numpy" not in sys.modules, "numpy was imported"
        """
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60
    )
    assert result.returncode == 0, result.stderr


# --------------------------------------------------------------------------------------------
# Fuzzing
# --------------------------------------------------------------------------------------------

FORMULA_CHARS = "0123456789.eE+-*/^() ,<>=!xyπτ√²³−×·÷pisqrtandornot_[]'"


@settings(max_examples=300, deadline=None)
@given(text=st.text(max_size=60), logic=st.booleans())
def test_any_text_raises_only_answer_format_error(text: str, logic: bool) -> None:
    try:
        ex = compile_expression(text, ["x", "y"], logic=logic)
    except AnswerFormatError:
        return
    with contextlib.suppress(AnswerFormatError):
        ex.evaluate({"x": 0.5, "y": -2.0})


@settings(max_examples=400, deadline=None)
@given(text=st.text(alphabet=FORMULA_CHARS, max_size=40), logic=st.booleans())
def test_formula_like_text_raises_only_answer_format_error(text: str, logic: bool) -> None:
    try:
        ex = compile_expression(text, ["x", "y"], logic=logic)
    except AnswerFormatError:
        return
    assert ex.names <= {"x", "y"}
    try:
        result = ex.evaluate({"x": 0.5, "y": -2.0})
    except AnswerFormatError:
        return
    if ex.is_condition:
        assert isinstance(result, bool)
    else:
        assert isinstance(result, float) and math.isfinite(result)
        array = ex.evaluate({"x": np.array([0.5]), "y": np.array([-2.0])}, backend="numpy")
        assert array.tolist() == pytest.approx([result], rel=1e-9, abs=1e-12)
