"""Drawing an exercise's parameters: variant 0 is canonical, variant s ≥ 1 is random but fixed.

Pure Python (``random.Random`` seeded with a string, which is stable across runs and platforms)
so that showing a prompt never needs numpy.
"""

from __future__ import annotations

import random
from typing import Any

from slamcourse.course.model import ExerciseSpec, ParamSpec, Variant
from slamcourse.errors import AnswerFormatError, CourseError, Problem

MAX_DRAWS = 1000


def variant(spec: ExerciseSpec, seed: int) -> Variant:
    """The parameters of variant ``seed`` of ``spec`` (0 = canonical)."""
    if seed < 0:
        raise ValueError("variant seeds are ≥ 0")
    rng = random.Random(f"{spec.id}:{seed}")
    for _ in range(MAX_DRAWS):
        params = _draw(spec, rng, canonical=seed == 0)
        failed = _failed_requirement(spec, params)
        if failed is None:
            return Variant(seed, params)
        if seed == 0:
            raise CourseError(
                Problem(
                    _rel(spec),
                    failed.line,
                    f"the canonical parameters fail 'require: {failed.source}'",
                )
            )
    raise CourseError(
        Problem(
            _rel(spec),
            spec.require[0].line if spec.require else spec.line,
            f"variant {seed}: no draw in {MAX_DRAWS} satisfied 'require'; "
            "widen the parameter ranges or relax the requirement",
        )
    )


def _draw(spec: ExerciseSpec, rng: random.Random, *, canonical: bool) -> dict[str, Any]:
    params: dict[str, Any] = {}
    for p in spec.parameters:
        params[p.name] = _value(spec, p, rng, params, canonical)
    return params


def _value(
    spec: ExerciseSpec, p: ParamSpec, rng: random.Random, known: dict[str, Any], canonical: bool
) -> Any:
    if p.dist == "value":
        return p.args[0]
    if p.dist == "expr":
        return _evaluate(spec, p, p.args[0], known)
    if canonical:
        value = p.canonical
        if isinstance(value, str):
            value = _evaluate(spec, p, value, known)
        return value
    if p.dist == "int":
        return rng.randint(int(p.args[0]), int(p.args[1]))
    if p.dist == "choice":
        return rng.choice(p.args)
    value = rng.uniform(float(p.args[0]), float(p.args[1]))
    if p.round is not None:
        value = round(value, p.round)
        if p.round <= 0:
            value = float(int(value))
    return value


def _evaluate(spec: ExerciseSpec, p: ParamSpec, text: str, known: dict[str, Any]) -> float:
    from slamcourse.answers.expr import compile_expression

    try:
        return float(compile_expression(text, known.keys()).evaluate(known))
    except AnswerFormatError as exc:
        raise CourseError(Problem(_rel(spec), p.line, f"parameter '{p.name}': {exc}")) from None


def _failed_requirement(spec: ExerciseSpec, params: dict[str, Any]) -> Any:
    if not spec.require:
        return None
    from slamcourse.answers.expr import compile_expression

    for req in spec.require:
        try:
            ok = compile_expression(req.source, params.keys(), logic=True).evaluate(params)
        except AnswerFormatError as exc:
            raise CourseError(
                Problem(_rel(spec), req.line, f"require '{req.source}': {exc}")
            ) from None
        if not ok:
            return req
    return None


def _rel(spec: ExerciseSpec) -> str:
    from slamcourse.errors import relpath

    return relpath(spec.path, spec.course_root)
