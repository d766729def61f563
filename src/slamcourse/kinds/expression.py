"""The ``expression`` kind: a formula in named variables, graded at many random points."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from typing import Any, ClassVar

from slamcourse.answers import compile_expression, format_number
from slamcourse.course import reference
from slamcourse.course.model import ExerciseSpec, Tolerance, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict
from slamcourse.errors import AnswerFormatError, Problem
from slamcourse.kinds.base import (
    Kind,
    course_error,
    misconception_verdict,
    problem,
)
from slamcourse.verdict import Verdict

EXPRESSION_TOLERANCE = Tolerance(rtol=1e-6, atol=1e-9)
_FORMS = {"uniform": "range", "int": "int-range", "expr": "text"}


@dataclass(frozen=True)
class Variable:
    name: str
    dist: str  # "uniform", "int" or "expr"
    args: tuple[Any, ...]
    line: int


@dataclass(frozen=True)
class ExpressionOptions:
    variables: tuple[Variable, ...]
    points: int
    answer: str | None
    tolerance: Tolerance


class ExpressionKind(Kind):
    """A formula such as ``-dx/sqrt(q)``: equal to the reference at every sampled point."""

    name: ClassVar[str] = "expression"
    keys: ClassVar[dict[str, bool]] = {"variables": True, "points": False, "answer": False}

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> ExpressionOptions:
        super().parse(spec, raw, check)
        variables: list[Variable] = []
        data = check.mapping(raw.get("variables"), raw.line_of("variables"), "'variables'")
        for name, value in (data or {}).items():
            line = data.line_of(name) if data else raw.line
            item = check.mapping(value, line, f"variable '{name}'")
            if item is None:
                continue
            check.keys(item, _FORMS, (), f"variable '{name}'")
            found = check.distribution(item, _FORMS, f"variable '{name}'")
            if found is None:
                continue
            variables.append(Variable(name, found[0], found[1], line))
        points = check.typed(raw, "points", int, 50)
        if points < 5:
            check.add(raw.line_of("points"), "'points' must be at least 5")
        tol = spec.tolerance if "tolerance" in raw else EXPRESSION_TOLERANCE
        return ExpressionOptions(tuple(variables), points, check.typed(raw, "answer", str), tol)

    # ---- sampling and evaluation
    def sample(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        """The sample points of this variant: one numpy array per variable (deterministic)."""
        import numpy as np

        opts: ExpressionOptions = spec.options
        digest = hashlib.sha256(f"{spec.id}:{variant.seed}:points".encode()).digest()
        rng = np.random.default_rng(int.from_bytes(digest[:8], "little"))
        env: dict[str, Any] = {}
        for var in opts.variables:
            if var.dist == "uniform":
                env[var.name] = rng.uniform(var.args[0], var.args[1], opts.points)
            elif var.dist == "int":
                env[var.name] = rng.integers(var.args[0], var.args[1] + 1, opts.points).astype(
                    float
                )
            else:
                try:
                    expr = compile_expression(var.args[0], env.keys())
                except AnswerFormatError as exc:
                    raise course_error(spec, var.line, f"variable '{var.name}': {exc}") from None
                env[var.name] = expr.evaluate(env, backend="numpy")
        return env

    def _values(
        self, spec: ExerciseSpec, name: str, line: int, variant: Variant, env: dict[str, Any]
    ) -> Any:
        import numpy as np

        raw = reference.call(spec, name, line, {**variant.params, **env})
        values = np.broadcast_to(np.asarray(raw, dtype=float), (spec.options.points,))
        return values

    def reference_calls(
        self, spec: ExerciseSpec, variant: Variant
    ) -> list[tuple[str, int, dict[str, Any]]]:
        """None a batch could share: the reference and the misconceptions are evaluated at the
        sampled points (arrays, never kept)."""
        return []

    def expected(self, spec: ExerciseSpec, variant: Variant) -> Any:
        assert spec.reference is not None
        return self._values(
            spec, spec.reference, spec.reference_line, variant, self.sample(spec, variant)
        )

    def _matches(self, spec: ExerciseSpec, got: Any, want: Any) -> Any:
        """Index of the first sample point where ``got`` differs, or ``None`` when all agree."""
        import numpy as np

        tol: Tolerance = spec.options.tolerance
        defined = np.isfinite(want)
        with np.errstate(all="ignore"):
            close = np.abs(got - want) <= tol.atol + tol.rtol * np.abs(want)
        bad = np.flatnonzero(defined & ~(close & np.isfinite(got)))
        return int(bad[0]) if bad.size else None

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        import numpy as np

        opts: ExpressionOptions = spec.options
        names = [v.name for v in opts.variables]
        try:
            expr = compile_expression(answer, names)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        env = self.sample(spec, variant)
        got = np.broadcast_to(
            np.asarray(expr.evaluate(env, backend="numpy"), dtype=float), (opts.points,)
        )
        want = self.expected(spec, variant)
        bad = self._matches(spec, got, want)
        if bad is None:
            return Verdict.ok(
                f"Your formula agrees with the reference at all {opts.points} test points."
            )
        for m in spec.misconceptions:
            assert m.compute is not None
            if (
                self._matches(spec, got, self._values(spec, m.compute, m.line, variant, env))
                is None
            ):
                return misconception_verdict(spec, m, variant, "Not quite.")
        at = ", ".join(f"{n} = {format_number(float(env[n][bad]))}" for n in names)
        if self._matches(spec, -got, want) is None:
            return Verdict.wrong("Not quite: your formula has the wrong sign everywhere.")
        return Verdict.wrong(
            f"Not quite: at {at} your formula gives "
            f"{format_number(float(got[bad]))}, but the right value is "
            f"{format_number(float(want[bad]))}.",
            point={n: float(env[n][bad]) for n in names},
        )

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        names = [v.name for v in spec.options.variables]
        from slamcourse.answers.expr import FUNCTIONS

        return {"type": "expression", "variables": names, "functions": sorted(FUNCTIONS)}

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        names = ", ".join(v.name for v in spec.options.variables)
        return (
            f"Answer with a formula in {names} (e.g. {self.example(spec, variant)}); you may "
            "use + - * / ^, sqrt, sin, cos, atan2, pi."
        )

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        v = [var.name for var in spec.options.variables] or ["x"]
        a, b = v[0], v[-1]
        return [f"2*{a} + sqrt({b})", f"{a}^2 - 3*{b}", f"sin({a}) / (1 + {b}^2)"]

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        opts: ExpressionOptions = spec.options
        problems: list[Problem] = []
        env = self.sample(spec, variant)
        want = self.expected(spec, variant)
        import numpy as np

        if np.count_nonzero(np.isfinite(want)) < opts.points // 2:
            problems.append(
                problem(
                    spec,
                    spec.reference_line,
                    "the reference is undefined at "
                    "most sample points; narrow the variables' ranges",
                )
            )
        if opts.answer is not None:
            verdict = self.check(spec, variant, opts.answer)
            if not verdict.passed:
                problems.append(
                    problem(
                        spec,
                        spec.line,
                        f"'answer: {opts.answer}' is not accepted: {verdict.feedback}",
                    )
                )
        for m in spec.misconceptions:
            assert m.compute is not None
            if (
                self._matches(spec, self._values(spec, m.compute, m.line, variant, env), want)
                is None
            ):
                problems.append(
                    problem(
                        spec,
                        m.line,
                        f"misconception '{m.id}' equals the "
                        "reference at every sample point, so it would be accepted",
                    )
                )
        return problems
