"""What every exercise kind provides, and helpers the kinds share."""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any, ClassVar

from slamcourse.course import reference, templates
from slamcourse.course.model import ExerciseSpec, Misconception, Text, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict
from slamcourse.errors import CourseError, Problem, relpath
from slamcourse.verdict import Verdict


class Kind(ABC):
    """Base class of exercise kinds (stateless; one shared instance per kind)."""

    name: ClassVar[str] = ""
    keys: ClassVar[dict[str, bool]] = {}  # kind-specific YAML keys -> required?
    reference_required: ClassVar[bool] = True
    misconception_key: ClassVar[str | None] = "compute"
    misconceptions_from_params: ClassVar[bool] = False  # (misconception_value computes them)

    # ---- loading
    def reference_optional(self, raw: LineDict) -> bool:
        """Whether this file may omit ``reference`` (e.g. choices marked ``correct: true``)."""
        return False

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> Any:
        """Parse the kind-specific keys (already checked to be known) into ``spec.options``."""
        for m in spec.misconceptions:
            key = self.misconception_key
            other = "function" if key == "compute" else "compute"
            if key is None:
                check.add(
                    m.line,
                    f"{self.name} exercises take feedback per choice or line, not 'misconceptions'",
                )
            elif getattr(m, other):
                check.add(
                    m.line,
                    f"misconception '{m.id}': a {self.name} exercise uses '{key}:', not '{other}:'",
                )
            elif not getattr(m, key):
                check.add(
                    m.line, f"misconception '{m.id}' needs '{key}: <function in reference.py>'"
                )
        return None

    # ---- answering (every kind implements these two)
    @abstractmethod
    def expected(self, spec: ExerciseSpec, variant: Variant) -> Any:
        """The reference answer of ``variant``."""

    @abstractmethod
    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        """Grade ``answer``; a learner's mistake is a verdict, never an exception."""

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        """One line telling the learner what form of answer is expected and what is accepted."""
        return ""

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        """Answers that show the input form (``how_to_answer`` shows the first safe one)."""
        return []

    def example(self, spec: ExerciseSpec, variant: Variant) -> str | None:
        """An example of the input form that is *not* a right answer of this variant, nor a
        declared misconception: a readable answer that fails with no misconception named.
        None when every candidate is unsafe (the validator reports that)."""
        for text in self.example_candidates(spec, variant):
            verdict = self.check(spec, variant, text)
            if verdict.status == "failed" and verdict.misconception is None:
                return text
        return None

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        """The expected input form as data: ``{"type": <kind>, ...}`` with the shape, units,
        options, items or listing a face needs to render an input (see docs/architecture.md)."""
        return {"type": self.name}

    # ---- sharing
    def reference_calls(
        self, spec: ExerciseSpec, variant: Variant
    ) -> list[tuple[str, int, dict[str, Any]]]:
        """The ``reference.py`` calls (function, line, arguments) that grading an answer to
        ``variant`` may make, the answer's first: a batch makes those of an answer that is the
        same for every learner once, for all its grading processes (kept results:
        :func:`~slamcourse.course.reference.kept_results`). The reference's, and its
        misconceptions' where this kind computes them from the variant's parameters alone."""
        if spec.reference is None:
            return []
        calls = [_reference_call(spec, variant)]
        if self.misconceptions_from_params:
            calls += [
                _misconception_call(spec, m, variant) for m in spec.misconceptions if m.compute
            ]
        return calls

    # ---- validation
    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        """Prove the variant sound: the reference passes; misconceptions fail and are named."""
        return []

    def example_problems(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        """The validator's check that the prompt never gives the answer away by its example."""
        if self.example_candidates(spec, variant) and self.example(spec, variant) is None:
            return [
                problem(
                    spec,
                    spec.line,
                    f"variant {variant.seed}: every example of the input form "
                    f"({', '.join(self.example_candidates(spec, variant))}) is a right answer "
                    "or a declared misconception, so the prompt would give it away; add a "
                    "'require' that avoids such variants",
                )
            ]
        return []


# ---------------------------------------------------------------------------- helpers


def _reference_call(spec: ExerciseSpec, variant: Variant) -> tuple[str, int, dict[str, Any]]:
    """The reference call grading ``variant`` makes (function, line, arguments): the one place
    that says it, so that a result a batch computed ahead (:meth:`Kind.reference_calls`) is
    the one found when grading."""
    assert spec.reference is not None
    return spec.reference, spec.reference_line, dict(variant.params)


def _misconception_call(
    spec: ExerciseSpec, m: Misconception, variant: Variant
) -> tuple[str, int, dict[str, Any]]:
    """The call reproducing misconception ``m`` for ``variant`` (see :func:`_reference_call`)."""
    assert m.compute is not None
    return m.compute, m.line, dict(variant.params)


def call_reference(spec: ExerciseSpec, variant: Variant) -> Any:
    return reference.call(spec, *_reference_call(spec, variant))


def misconception_value(spec: ExerciseSpec, m: Misconception, variant: Variant) -> Any:
    return reference.call(spec, *_misconception_call(spec, m, variant))


def render(spec: ExerciseSpec, text: Text, variant: Variant, **extra: Any) -> str:
    return templates.render(spec, text, {**variant.params, **extra})


def problem(spec: ExerciseSpec, line: int | None, message: str) -> Problem:
    return Problem(relpath(spec.path, spec.course_root), line, message)


def course_error(spec: ExerciseSpec, line: int | None, message: str) -> CourseError:
    return CourseError(problem(spec, line, message))


def misconception_verdict(
    spec: ExerciseSpec, m: Misconception, variant: Variant, lead: str, **details: Any
) -> Verdict:
    message = render(spec, m.message, variant)
    return Verdict.wrong(f"{lead} {message}".strip(), misconception=m.id, **details)


def expect_misconceptions(
    spec: ExerciseSpec, variant: Variant, check: Any, answer_for: Any
) -> list[Problem]:
    """Shared validator step: each misconception's answer must fail and be recognised."""
    problems = []
    for m in spec.misconceptions:
        text = answer_for(m)
        verdict = check(spec, variant, text)
        where = f"variant {variant.seed}"
        if verdict.passed:
            problems.append(
                problem(
                    spec,
                    m.line,
                    f"misconception '{m.id}' is accepted in {where} "
                    f"(its answer {text} is within the tolerance of the reference); "
                    "tighten the tolerance or add a 'require' that keeps them apart",
                )
            )
        elif verdict.misconception != m.id:
            got = verdict.misconception or "no misconception"
            problems.append(
                problem(
                    spec,
                    m.line,
                    f"misconception '{m.id}' is not recognised in "
                    f"{where}: its answer {text} matched {got}",
                )
            )
    return problems
