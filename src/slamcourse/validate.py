"""``slamcourse validate``: prove every exercise of a course sound, on many variants."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from slamcourse.course import templates, variants
from slamcourse.course.loader import Course, load_course
from slamcourse.course.model import ExerciseSpec
from slamcourse.errors import CourseError, GraderError, Problem, relpath
from slamcourse.kinds import get_kind


@dataclass
class Report:
    """What validation found: problems (``path:line: message``) and what was covered."""

    problems: list[Problem] = field(default_factory=list)
    exercises: int = 0
    variants: int = 0

    @property
    def ok(self) -> bool:
        return not self.problems


def validate_course(
    root: Path, *, variants_per_exercise: int = 25, progress: Callable[[str], None] | None = None
) -> Report:
    """Load every chapter and exercise of the course at ``root`` and check each one."""
    course = load_course(root)
    report = Report(list(course.problems))
    placed = set(course.exercise_ids)
    for path in sorted((root / "exercises").glob("*/*.yaml")):
        ex_id = f"{path.parent.name}/{path.stem}"
        if ex_id not in placed:
            report.problems.append(
                Problem(
                    relpath(path, root),
                    1,
                    f"exercise '{ex_id}' is not "
                    "placed in any chapter; add a ```{exercise} "
                    f"{ex_id} block to its chapter",
                )
            )
            continue
        if progress:
            progress(ex_id)
        report.problems.extend(validate_exercise(course, ex_id, variants_per_exercise, report))
    return report


def validate_exercise(
    course: Course, exercise_id: str, count: int, report: Report | None = None
) -> list[Problem]:
    """Problems of one exercise over the canonical variant and ``count`` random ones."""
    try:
        spec = course.exercise(exercise_id)
    except CourseError as exc:
        return exc.problems
    if report is not None:
        report.exercises += 1
    kind = get_kind(spec.kind)
    seeds = [0] + (list(range(1, count + 1)) if spec.has_variants else [])
    first: dict[tuple[str, int | None], Problem] = {}  # one report per place...
    seen_in: dict[tuple[str, int | None], int] = {}  # ...with the number of variants it hit
    checked = 0
    for seed in seeds:
        try:
            variant = variants.variant(spec, seed)
            _render_all(spec, variant.params, kind.expected(spec, variant))
            found = kind.self_test(spec, variant)
        except CourseError as exc:
            found = exc.problems
        except GraderError as exc:  # e.g. the reference fails on an input the strategy drew
            found = [Problem(relpath(spec.path, spec.course_root), spec.line, str(exc))]
        checked += 1
        if report is not None:
            report.variants += 1
        for p in found:
            key = (p.path, p.line)
            first.setdefault(key, p)
            seen_in[key] = seen_in.get(key, 0) + 1
    problems = []
    for key, p in first.items():
        times = seen_in[key]
        suffix = f" (in {times} of {checked} variants checked)" if checked > 1 and times > 1 else ""
        problems.append(Problem(p.path, p.line, p.message + suffix))
    return problems


def _render_all(spec: ExerciseSpec, params: dict[str, object], answer: object) -> None:
    templates.render(spec, spec.prompt, dict(params))
    templates.render(spec, spec.explanation, {**params, "answer": answer})
    for hint in spec.hints:
        templates.render(spec, hint, dict(params))
    for m in spec.misconceptions:
        templates.render(spec, m.message, dict(params))
