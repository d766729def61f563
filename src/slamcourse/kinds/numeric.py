"""Numeric kinds: ``number``, ``vector`` and ``matrix``, compared with |a − b| ≤ atol + rtol·|b|."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

from slamcourse.answers import (
    angle_is_close,
    compare_entries,
    format_number,
    is_close,
    parse_integer,
    parse_matrix,
    parse_number,
    parse_vector,
    plural,
    tolerance_window,
)
from slamcourse.course.model import ExerciseSpec, Misconception, Tolerance, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict
from slamcourse.errors import AnswerFormatError, Problem
from slamcourse.kinds.base import (
    Kind,
    call_reference,
    course_error,
    expect_misconceptions,
    misconception_value,
    misconception_verdict,
    problem,
)
from slamcourse.verdict import Verdict


@dataclass(frozen=True)
class NumericOptions:
    exact: bool = False
    angle: bool | tuple[int, ...] = False
    units: str = ""
    labels: tuple[str, ...] = ()


def describe_tolerance(tol: Tolerance, exact: bool) -> str:
    """``within 1%`` / ``within ±0.005`` / ``within ±(0.005 + 1%)``, as told to learners."""
    if exact:
        return "exactly"
    rel = f"{tol.rtol * 100:g}%" if tol.rtol > 0 else ""
    abs_ = f"{format_number(tol.atol)}" if tol.atol >= 1e-6 else ""
    if rel and abs_:
        return f"within ±({abs_} + {rel} of the value)"
    if rel:
        return f"within {rel}"
    if abs_:
        return f"within ±{abs_}"
    return "to full precision"


def _parse_options(raw: LineDict, check: Checker, *, vector: bool) -> NumericOptions:
    exact = bool(check.typed(raw, "exact", bool, False))
    angle_raw = raw.get("angle", False)
    angle: bool | tuple[int, ...] = False
    if isinstance(angle_raw, bool):
        angle = angle_raw
    elif (
        vector
        and isinstance(angle_raw, list)
        and all(isinstance(i, int) and not isinstance(i, bool) and i >= 0 for i in angle_raw)
    ):
        angle = tuple(angle_raw)
    else:
        form = "true, or a list of 0-based entry indices such as [1]" if vector else "true or false"
        check.add(raw.line_of("angle"), f"'angle' must be {form}")
    if exact and angle:
        check.add(raw.line_of("angle"), "an answer cannot be both 'exact' and an 'angle'")
    labels = check.typed(raw, "labels", list, []) if vector else []
    return NumericOptions(
        exact, angle, str(check.typed(raw, "units", str, "")), tuple(str(x) for x in labels)
    )


def _to_float(spec: ExerciseSpec, value: Any, what: str, exact: bool) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):
        raise course_error(
            spec, spec.reference_line, f"{what} must be a number, got {value!r}"
        ) from None
    if not math.isfinite(number):
        raise course_error(spec, spec.reference_line, f"{what} is not finite ({number})")
    if exact and number != round(number):
        raise course_error(
            spec,
            spec.reference_line,
            f"{what} is {number}, not a whole number, but the exercise is 'exact'",
        )
    return number


class NumberKind(Kind):
    """A single number; optional ``exact`` integers and ``angle`` comparison modulo 2π."""

    name: ClassVar[str] = "number"
    misconceptions_from_params = True
    keys: ClassVar[dict[str, bool]] = {"exact": False, "angle": False, "units": False}

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> NumericOptions:
        super().parse(spec, raw, check)
        return _parse_options(raw, check, vector=False)

    def expected(self, spec: ExerciseSpec, variant: Variant) -> float:
        value = _to_float(
            spec, call_reference(spec, variant), "the reference answer", spec.options.exact
        )
        return round(value) if spec.options.exact else value  # 108, not 108.0, in templates

    def accepts(self, spec: ExerciseSpec, got: float, want: float) -> bool:
        opts: NumericOptions = spec.options
        tol = spec.tolerance
        if opts.exact:
            return got == want
        if opts.angle:
            return angle_is_close(got, want, tol.rtol, tol.atol)
        return is_close(got, want, tol.rtol, tol.atol)

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        opts: NumericOptions = spec.options
        try:
            got = (
                float(parse_integer(answer, opts.units))
                if opts.exact
                else parse_number(answer, opts.units)
            )
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        want = self.expected(spec, variant)
        units = f" {opts.units}" if opts.units else ""
        if self.accepts(spec, got, want):
            if opts.exact:
                return Verdict.ok(f"Exactly {format_number(want)}{units}.", expected=want)
            lo, hi = tolerance_window(want, spec.tolerance.rtol, spec.tolerance.atol)
            mod = " (modulo 2π)" if opts.angle else ""
            return Verdict.ok(
                f"The reference value is {format_number(want)}{units}; answers from "
                f"{format_number(lo)} to {format_number(hi)}{mod} are accepted.",
                expected=want,
                window=[lo, hi],
            )
        lead = f"Not quite: {format_number(got)}{units} is not accepted."
        for m in spec.misconceptions:
            if self.accepts(
                spec,
                got,
                _to_float(
                    spec, misconception_value(spec, m, variant), f"misconception '{m.id}'", False
                ),
            ):
                return misconception_verdict(spec, m, variant, lead, got=got)
        return Verdict.wrong(f"{lead} {self._diagnose(spec, got, want)}".strip(), got=got)

    def _diagnose(self, spec: ExerciseSpec, got: float, want: float) -> str:
        """Generic, safe observations about a wrong number (never the answer itself)."""
        opts: NumericOptions = spec.options
        if want != 0 and self.accepts(spec, -got, want):
            return "The size is right but the sign is wrong."
        if opts.angle and self.accepts(spec, math.radians(got), want):
            return "That looks like degrees; give the angle in radians (e.g. pi/4 or 0.785)."
        if want != 0 and got != 0 and math.isfinite(got) and not opts.exact:
            # a difference of logarithms, not log10(got / want): the quotient overflows to
            # inf (1e308 / 0.1) or underflows to 0 (5e-324 / 10), and log10 of either raises
            ratio = math.log10(abs(got)) - math.log10(abs(want))
            k = round(ratio)
            if k != 0 and abs(ratio - k) < 0.01:
                return (
                    f"Your value is off by a factor of 10^{k}: check the units and the "
                    "decimal point."
                )
        return ""

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        opts: NumericOptions = spec.options
        return {
            "type": "number",
            "units": opts.units or None,
            "integer": opts.exact,
            "angle": bool(opts.angle),
        }

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        opts: NumericOptions = spec.options
        units = f" in {opts.units}" if opts.units else ""
        example = self.example(spec, variant)
        if opts.exact:
            return f"Answer with a whole number{units}, exactly (e.g. {example})."
        angle = " Angles are in radians and compared modulo 2π." if opts.angle else ""
        return (
            f"Answer with a number{units} (a decimal, a fraction, or a formula of numbers "
            f"with pi and sqrt, e.g. {example}); accepted "
            f"{describe_tolerance(spec.tolerance, False)}.{angle}"
        )

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        if spec.options.exact:
            return ["12", "7", "30", "101"]
        return ["7/5", "sqrt(2)/2", "0.25", "pi/4", "3.6"]

    def answer_text(self, value: float, exact: bool) -> str:
        return str(round(value)) if exact else repr(float(value))

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        want = self.expected(spec, variant)
        problems = []
        text = self.answer_text(want, spec.options.exact)
        verdict = self.check(spec, variant, text)
        if not verdict.passed:
            problems.append(
                problem(
                    spec,
                    spec.reference_line,
                    f"variant {variant.seed}: the "
                    f"reference answer {text} is not accepted: {verdict.feedback}",
                )
            )

        def answer_for(m: Misconception) -> str:
            value = _to_float(
                spec, misconception_value(spec, m, variant), f"misconception '{m.id}'", False
            )
            return self.answer_text(value, spec.options.exact and value == round(value))

        return problems + expect_misconceptions(spec, variant, self.check, answer_for)


class VectorKind(Kind):
    """A vector of numbers, compared entry by entry; ``angle`` marks entries compared mod 2π."""

    name: ClassVar[str] = "vector"
    misconceptions_from_params = True
    ndim: ClassVar[int] = 1
    keys: ClassVar[dict[str, bool]] = {
        "exact": False,
        "angle": False,
        "units": False,
        "labels": False,
    }

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> NumericOptions:
        super().parse(spec, raw, check)
        return _parse_options(raw, check, vector=self.ndim == 1)

    def _array(self, spec: ExerciseSpec, value: Any, what: str) -> list[Any]:
        import numpy as np

        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise course_error(
                spec, spec.reference_line, f"{what} must be a {self.name} of numbers, got {value!r}"
            ) from None
        if arr.ndim != self.ndim or arr.size == 0:
            raise course_error(
                spec,
                spec.reference_line,
                f"{what} must be a {self.ndim}-D {self.name}, got shape {arr.shape}",
            )
        if not np.all(np.isfinite(arr)):
            raise course_error(spec, spec.reference_line, f"{what} has non-finite entries")
        result: list[Any] = arr.tolist()
        return result

    def expected(self, spec: ExerciseSpec, variant: Variant) -> list[Any]:
        return self._array(spec, call_reference(spec, variant), "the reference answer")

    def _parse(self, answer: str) -> list[Any]:
        return parse_vector(answer)

    def _compare(self, spec: ExerciseSpec, got: list[Any], want: list[Any]) -> Any:
        opts: NumericOptions = spec.options
        return compare_entries(
            got, want, spec.tolerance.rtol, spec.tolerance.atol, angle=opts.angle, exact=opts.exact
        )

    def _entry_name(self, spec: ExerciseSpec, index: tuple[int, ...]) -> str:
        labels = spec.options.labels
        if self.ndim == 1:
            label = f" ({labels[index[0]]})" if index[0] < len(labels) else ""
            return f"{index[0] + 1}{label}"
        return "(" + ", ".join(str(i + 1) for i in index) + ")"

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        try:
            got = self._parse(answer)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        want = self.expected(spec, variant)
        result = self._compare(spec, got, want)
        if not result.shape_ok:  # a form error: the answer cannot be compared, no attempt
            return Verdict.unreadable(
                f"expected {self._shape_words(result.expected_shape)}, but your "
                f"answer has {self._shape_words(result.got_shape)}"
            )
        if result.ok:
            return Verdict.ok(
                f"Accepted {describe_tolerance(spec.tolerance, spec.options.exact)} "
                "entry by entry.",
                expected=want,
            )
        total = _size(want)
        score = (total - len(result.wrong)) / total
        lead = "Not quite."
        for m in spec.misconceptions:
            value = self._array(
                spec, misconception_value(spec, m, variant), f"misconception '{m.id}'"
            )
            if self._compare(spec, got, value).ok:
                return misconception_verdict(spec, m, variant, lead, wrong=_lists(result.wrong))
        negated = _negate(got)
        if self._compare(spec, negated, want).ok:
            return Verdict.wrong(
                f"{lead} Every entry has the wrong sign.", score=score, wrong=_lists(result.wrong)
            )
        names = ", ".join(self._entry_name(spec, i) for i in result.wrong)
        word = "entry" if len(result.wrong) == 1 else "entries"
        right = " The other entries are right." if len(result.wrong) < total else ""
        return Verdict.wrong(
            f"{lead} Wrong {word}: {names}.{right}", score=score, wrong=_lists(result.wrong)
        )

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        """The shape comes from the reference answer (computed only when a face asks)."""
        want = self.expected(spec, variant)
        opts: NumericOptions = spec.options
        if self.ndim == 1:
            labels = list(opts.labels)[: len(want)]
            return {
                "type": "vector",
                "length": len(want),
                "units": opts.units or None,
                "labels": labels,
            }
        return {"type": "matrix", "rows": len(want), "cols": len(want[0]) if want else 0}

    def _shape_words(self, shape: tuple[int, ...]) -> str:
        if len(shape) == 1:
            return plural(shape[0], "entry")
        if len(shape) == 2:
            return f"{plural(shape[0], 'row')} of {shape[1]}"
        return f"shape {shape}"

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        units = f" (in {spec.options.units})" if spec.options.units else ""
        tol = describe_tolerance(spec.tolerance, spec.options.exact)
        n = len(self.expected(spec, variant))
        example = self.example(spec, variant)
        return (
            f"Answer with a vector of {plural(n, 'entry')}{units}, e.g. {example} (brackets "
            f"and commas optional); each entry accepted {tol}."
        )

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        n = len(self.expected(spec, variant))
        exact = spec.options.exact
        pools = (
            ([2, -1, 4, 3, -5, 6], [1, 3, -2, 5, 4, -3])
            if exact
            else (
                [0.3, -1.2, 2.5, 0.75, -4.1, 1.6],
                [1.5, 0.4, -0.8, 3.2, -2.25, 0.9],
            )
        )
        return [
            "["
            + ", ".join(format_number(pool[i % len(pool)] * (1 + i // len(pool))) for i in range(n))
            + "]"
            for pool in pools
        ]

    def answer_text(self, value: list[Any]) -> str:
        return repr(value)

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        want = self.expected(spec, variant)
        problems = []
        verdict = self.check(spec, variant, self.answer_text(want))
        if not verdict.passed:
            problems.append(
                problem(
                    spec,
                    spec.reference_line,
                    f"variant {variant.seed}: the "
                    f"reference answer {want} is not accepted: {verdict.feedback}",
                )
            )

        def answer_for(m: Misconception) -> str:
            return self.answer_text(
                self._array(spec, misconception_value(spec, m, variant), f"misconception '{m.id}'")
            )

        return problems + expect_misconceptions(spec, variant, self.check, answer_for)


class MatrixKind(VectorKind):
    """A matrix of numbers (``[[1, 2], [3, 4]]`` or ``[1 2; 3 4]``), compared entry by entry."""

    name: ClassVar[str] = "matrix"
    ndim: ClassVar[int] = 2
    keys: ClassVar[dict[str, bool]] = {"exact": False, "angle": False, "units": False}

    def _parse(self, answer: str) -> list[Any]:
        return parse_matrix(answer)

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        tol = describe_tolerance(spec.tolerance, spec.options.exact)
        want = self.expected(spec, variant)
        rows, cols = len(want), len(want[0])
        # the example is written in letters, so it can never be an answer
        return (
            f"Answer with a {rows}×{cols} matrix, row by row: [[a, b], [c, d]] or "
            f"[a b; c d] for a 2×2 one; each entry accepted {tol}."
        )

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        return []


def _size(value: list[Any]) -> int:
    return sum(_size(v) for v in value) if isinstance(value, list) else 1


def _negate(value: Any) -> Any:
    return [_negate(v) for v in value] if isinstance(value, list) else -value


def _lists(indices: list[tuple[int, ...]]) -> list[list[int]]:
    return [list(i) for i in indices]
