"""Every exercise of the real course is itself tested: the validator's checks, one test each
(reference accepted on many variants, misconceptions rejected and recognised, code starters fail
and solutions pass, every mutant is rejected and every correct variant passes, all in the real
sandbox), plus the checks ``slamcourse validate`` makes of the course as a whole.

This is the one place the suite validates the bundled course: ``scripts/test.sh`` runs the
``slamcourse validate`` command on a single exercise only (its command-line face), and the
chapters' own test files need not grade a shipped mutant, variant, solution or starter again:
they test what the validator does not (a misconception named, a mutant caught by a given
mechanism).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from slamcourse import validate
from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.errors import Problem
from slamcourse.kinds.code import CodeKind, submission_files
from slamcourse.verdict import Verdict

ROOT = bundled_course_root()
COURSE = load_course(ROOT)
VARIANTS = 20  # random variants per exercise, besides the canonical one

# Chapters whose mutants must be graded ``failed`` (a readable wrong answer), not merely "not
# passed" as the validator asks (which also accepts ``timeout``): what their former per-mutant
# tests (test_mutants_ch1_4.py, test_mutants_ch5_8.py, test_beyond_geometry.py) required.
MUTANTS_FAIL_NOT_TIME_OUT = {
    "state",
    "observation",
    "association",
    "drift",
    "graph",
    "vision",
    "factor-graphs",
    "occupancy",
    "orderings",
    "scan-matching",
}


def test_course_index_has_no_problems() -> None:
    assert COURSE.problems == []
    assert [c.id for c in COURSE.chapters][:2] == ["state", "observation"]


def test_the_course_as_a_whole_is_sound(monkeypatch: pytest.MonkeyPatch) -> None:
    """What ``validate_course`` checks besides each exercise (every exercise file placed in a
    chapter, every placed figure draws accessible SVG, the course loads without problems), with
    the per-exercise validation left to :func:`test_exercise_is_sound` (so it runs once): the
    validator must hand it exactly the exercises that test is parametrized with."""
    handed: list[str] = []

    def one_exercise(
        course: Any, exercise_id: str, count: int, *args: Any, **kw: Any
    ) -> list[Problem]:
        assert count == VARIANTS
        handed.append(exercise_id)
        return []

    monkeypatch.setattr(validate, "validate_exercise", one_exercise)
    report = validate.validate_course(ROOT, variants_per_exercise=VARIANTS)
    assert [str(p) for p in report.problems] == []
    assert sorted(handed) == sorted(COURSE.exercise_ids)


def test_every_mutant_and_variant_belongs_and_says_what_it_is() -> None:
    """Every file in a ``mutants/<slug>/`` or ``variants/<slug>/`` folder belongs to a code
    exercise of the course (so the validation grades it), and its first line names its mistake
    (``# mistake: …``) or its method (``# method: …``) in a few words (the validator only asks
    for the tag)."""
    code = {ex for ex in COURSE.exercise_ids if COURSE.exercise(ex).kind == "code"}
    for role, tag in (("mutants", "# mistake: "), ("variants", "# method: ")):
        for path in sorted(ROOT.glob(f"exercises/*/{role}/*/*.py")):
            exercise_id = f"{path.parent.parent.parent.name}/{path.parent.name}"
            assert exercise_id in code, f"{path}: no code exercise {exercise_id} to grade it"
            first = path.read_text(encoding="utf-8").splitlines()[0]
            assert first.startswith(tag) and len(first) > len(tag) + 5, f"{path}: {first!r}"


def _record_gradings(monkeypatch: pytest.MonkeyPatch) -> dict[tuple[str, str], Verdict]:
    """Every verdict the code kind gives from now on, by (file name, source)."""
    seen: dict[tuple[str, str], Verdict] = {}
    grade = CodeKind.check_source

    def recorded(self: CodeKind, spec: Any, source: str, filename: str, **kw: Any) -> Verdict:
        verdict = grade(self, spec, source, filename, **kw)
        seen[(filename, source)] = verdict  # the validator's threads write distinct keys
        return verdict

    monkeypatch.setattr(CodeKind, "check_source", recorded)
    return seen


@pytest.mark.parametrize("exercise_id", COURSE.exercise_ids)
def test_exercise_is_sound(exercise_id: str, monkeypatch: pytest.MonkeyPatch) -> None:
    spec = COURSE.exercise(exercise_id)
    graded = _record_gradings(monkeypatch)
    problems = validate.validate_exercise(COURSE, exercise_id, VARIANTS)
    assert [str(p) for p in problems] == []
    if spec.kind != "code":
        return
    mutants, variants = submission_files(spec)
    files: list[Path] = [spec.options.solution, spec.options.starter, *mutants, *variants]
    for path in files:  # each graded in the sandbox, once, by the validation above
        assert (path.name, path.read_bytes().decode("utf-8")) in graded, f"{path} not graded"
    if exercise_id.split("/")[0] in MUTANTS_FAIL_NOT_TIME_OUT:
        for path in mutants:
            verdict = graded[(path.name, path.read_bytes().decode("utf-8"))]
            assert verdict.status == "failed", f"{path.name} ({verdict.status}): {verdict.feedback}"
