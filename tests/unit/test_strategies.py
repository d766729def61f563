"""Inputs drawn for code exercises stay in a physical range: no NaN, infinity or subnormal,
no magnitudes below the range's resolution other than 0, 12 significant digits."""

from __future__ import annotations

import math
import sys

from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.grading.strategies import Argument, real, realistic, strategy_for

FLOATS = (
    Argument("x", "float", (-50, 50), 1),
    Argument("t", "float", (-3.15, 3.15), 2),
    Argument("s", "float", (1e-4, 0.01), 3),
)


def is_realistic(x: float, low: float, high: float) -> bool:
    return (
        math.isfinite(x)
        and low <= x <= high
        and (x == 0.0 or abs(x) >= sys.float_info.min)  # never subnormal
        and (x == 0.0 or abs(x) >= min(1e-9, max(abs(low), abs(high)) * 1e-6))
        and float(f"{x:.12g}") == x
    )


@settings(max_examples=200, database=None)
@given(strategy_for(FLOATS, ()))
def test_declared_floats_are_realistic(kwargs: dict[str, float]) -> None:
    for arg in FLOATS:
        assert is_realistic(kwargs[arg.name], *arg.args), (arg.name, kwargs[arg.name])


@settings(max_examples=300, database=None)
@given(st.floats(allow_nan=False, allow_infinity=False, min_value=-1e3, max_value=1e3))
def test_the_rule_maps_any_float_of_the_range_into_it(x: float) -> None:
    assert is_realistic(realistic(x, -1e3, 1e3), -1e3, 1e3)


def test_the_rule_at_its_edges() -> None:
    assert realistic(5e-324, -1.0, 1.0) == 0.0
    assert realistic(-1e-10, -1.0, 1.0) == 0.0 and math.copysign(1, realistic(-0.0, -1, 1)) == 1
    assert realistic(2e-9, -1.0, 1.0) == 2e-9
    assert realistic(1e-11, -1e-6, 1e-6) == 1e-11  # a range in micro-units keeps its scale
    assert realistic(1e-13, -1e-6, 1e-6) == 0.0
    assert realistic(0.1 + 0.2, 0, 1) == 0.3
    assert realistic(math.pi, -math.pi, math.pi) <= math.pi  # rounding never leaves the range
    assert realistic(1e-12, 1e-12, 1.0) == 1e-12  # a range that excludes 0 is respected


@settings(max_examples=200, database=None)
@given(real(0.5, 2.0))
def test_real_for_reference_strategies(x: float) -> None:
    assert is_realistic(x, 0.5, 2.0)


def test_complex_number_observation_model_passes() -> None:
    """A correct observation_model written with complex numbers passes the real exercise,
    through the sandbox, and in-process on another seed of the same strategy."""
    from slamcourse.course import reference
    from slamcourse.course.loader import load_course
    from slamcourse.grading.properties import TrustedCallee, run
    from slamcourse.kinds import get_kind
    from tests.conftest import REPO

    source = (
        "import cmath\n\n"
        "def observation_model(xr, yr, thr, xj, yj):\n"
        "    z = complex(xj - xr, yj - yr)\n"
        "    return abs(z), cmath.phase(z * cmath.exp(-1j * thr))\n"
    )
    spec = load_course(REPO).exercise("observation/observation-model")
    kind = get_kind("code")
    verdict = kind.check_source(spec, source, "observation_model.py")  # type: ignore[attr-defined]
    assert verdict.passed, verdict.feedback
    namespace: dict[str, object] = {}
    exec(compile(source, "complex.py", "exec"), namespace)
    opts = spec.options
    for seed in (1,):
        outcome = run(
            strategy=kind.strategy(spec),  # type: ignore[attr-defined]
            examples=opts.examples,
            signature=opts.signature,
            returns=opts.returns,
            tolerance=opts.tolerance,
            reference=reference.function(spec, spec.reference or "", spec.reference_line),
            call=TrustedCallee(namespace["observation_model"]).call,  # type: ignore[arg-type]
            max_examples=opts.max_examples,
            seed=seed,
        )
        assert outcome.passed, outcome.failure
