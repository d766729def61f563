"""The ``line`` kind: find the buggy line of a listing; feedback for tempting wrong lines."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from slamcourse.answers import parse_integer
from slamcourse.course.model import ExerciseSpec, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict
from slamcourse.errors import AnswerFormatError, Problem
from slamcourse.kinds.base import Kind, problem
from slamcourse.verdict import Verdict


@dataclass(frozen=True)
class LineOptions:
    code: str
    language: str
    answer: int
    lines: dict[int, str]

    @property
    def count(self) -> int:
        return len(self.code.rstrip("\n").splitlines())


class LineKind(Kind):
    """Answer with the number of the line that holds the bug."""

    name: ClassVar[str] = "line"
    keys: ClassVar[dict[str, bool]] = {
        "code": True,
        "language": False,
        "answer": True,
        "lines": False,
    }
    reference_required: ClassVar[bool] = False
    misconception_key: ClassVar[str | None] = None

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> LineOptions:
        super().parse(spec, raw, check)
        code = str(check.typed(raw, "code", str, ""))
        answer = check.typed(raw, "answer", int, 1)
        lines_raw = check.typed(raw, "lines", dict, {})
        opts = LineOptions(code, str(check.typed(raw, "language", str, "python")), answer, {})
        for key, text in lines_raw.items():
            try:
                number = int(key)
            except ValueError:
                check.add(raw.line_of("lines"), f"'lines' keys are line numbers, not '{key}'")
                continue
            if not 1 <= number <= opts.count:
                check.add(
                    raw.line_of("lines"), f"line {number} is outside the listing (1–{opts.count})"
                )
            elif number == answer:
                check.add(
                    raw.line_of("lines"),
                    f"line {number} is the answer; 'lines' is for tempting wrong lines",
                )
            opts.lines[number] = str(text)
        if not 1 <= answer <= max(opts.count, 1):
            check.add(
                raw.line_of("answer"), f"'answer: {answer}' is outside the listing (1–{opts.count})"
            )
        if spec.reference:
            check.add(
                spec.reference_line,
                "a line exercise takes its answer from 'answer'; remove 'reference'",
            )
        return opts

    def expected(self, spec: ExerciseSpec, variant: Variant) -> int:
        answer: int = spec.options.answer
        return answer

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        opts: LineOptions = spec.options
        lines = opts.code.rstrip("\n").splitlines()
        return {"type": "line", "language": opts.language, "lines": lines}

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        return f"Answer with the number of the buggy line (1–{spec.options.count})."

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        opts: LineOptions = spec.options
        try:
            number = parse_integer(answer)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        if not 1 <= number <= opts.count:
            return Verdict.unreadable(f"the listing has lines 1 to {opts.count}")
        if number == opts.answer:
            return Verdict.ok(f"Line {number} holds the bug.")
        if number in opts.lines:
            return Verdict.wrong(f"Not line {number}. {opts.lines[number]}", line=number)
        return Verdict.wrong(
            f"Line {number} does what it should. Trace what each line computes "
            "and compare it with the mathematics.",
            line=number,
        )

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        opts: LineOptions = spec.options
        problems = []
        if not self.check(spec, variant, str(opts.answer)).passed:
            problems.append(problem(spec, spec.line, "the answer line is not accepted"))
        for number in opts.lines:
            if self.check(spec, variant, str(number)).passed:
                problems.append(problem(spec, spec.line, f"tempting line {number} is accepted"))
        return problems
