"""Broken courses: every authoring mistake is reported as path:line with a fix."""

from __future__ import annotations

from pathlib import Path

import pytest

from slamcourse.course.loader import load_course
from slamcourse.errors import CourseError
from slamcourse.validate import validate_course


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, f"{old!r} not in {path}"
    path.write_text(text.replace(old, new, 1))


def problems_of(course: Path) -> list[str]:
    """The problems, leaving out the shipped recording of the fixture's code exercise (edits
    of reference.py here make it stale; tests/engine/test_validate_submissions.py covers it)."""
    report = validate_course(course, variants_per_exercise=5, min_mutants=0, min_variants=0)
    return [str(p) for p in report.problems if "recording" not in p.message]


def only(problems: list[str]) -> str:
    assert len(problems) == 1, problems
    return problems[0]


def test_unknown_key_suggests_the_nearest(course_copy: Path) -> None:
    edit(course_copy / "exercises/basics/distance.yaml", "explanation:", "explanaton:")
    found = problems_of(course_copy)
    assert any(
        p.startswith("exercises/basics/distance.yaml:15: unknown key 'explanaton'")
        and "did you mean 'explanation'" in p
        for p in found
    ), found


def test_missing_reference_function(course_copy: Path) -> None:
    edit(course_copy / "exercises/basics/count.yaml", "reference: count", "reference: cnt")
    message = only(problems_of(course_copy))
    assert message.startswith("exercises/basics/count.yaml:8: reference.py has no function 'cnt'")
    assert "did you mean 'count'" in message


def test_accepted_misconception_is_reported(course_copy: Path) -> None:
    edit(
        course_copy / "exercises/basics/reference.py",
        "def count_forgot_pose(n):\n    return 2 * n",
        "def count_forgot_pose(n):\n    return 3 + 2 * n",
    )
    message = only(problems_of(course_copy))
    assert message.startswith(
        "exercises/basics/count.yaml:12: misconception 'forgot-pose' is accepted"
    )


def test_yaml_syntax_error(course_copy: Path) -> None:
    edit(course_copy / "exercises/basics/pick.yaml", "title: Pick one", "title: [Pick one")
    message = only(problems_of(course_copy))
    assert message.startswith("exercises/basics/pick.yaml:") and "YAML syntax error" in message


def test_template_error_names_the_line(course_copy: Path) -> None:
    edit(
        course_copy / "exercises/basics/distance.yaml",
        "{{ dy | num }})$ from",
        "{{ dz | num }})$ from",
    )
    message = only(problems_of(course_copy))
    assert message.startswith("exercises/basics/distance.yaml:6: template error")
    assert "dz" in message


def test_id_must_match_path(course_copy: Path) -> None:
    edit(course_copy / "exercises/basics/bug.yaml", "id: basics/bug", "id: basics/bugs")
    message = only(problems_of(course_copy))
    assert message.startswith("exercises/basics/bug.yaml:2: id 'basics/bugs' does not match")


def test_unplaced_exercise_and_missing_file(course_copy: Path) -> None:
    edit(
        course_copy / "chapters/01-basics.md",
        "```{exercise} basics/bug",
        "```{exercise} basics/bog",
    )
    found = problems_of(course_copy)
    assert any(
        p.startswith("chapters/01-basics.md:38: exercise 'basics/bog' has no file") for p in found
    ), found
    assert any(
        p.startswith("exercises/basics/bug.yaml:1: exercise 'basics/bug' is not placed")
        for p in found
    ), found


def test_newer_format_is_refused(course_copy: Path) -> None:
    edit(course_copy / "exercises/basics/pick.yaml", "format: 1", "format: 9")
    assert "newer than this slamcourse understands" in only(problems_of(course_copy))


def test_duplicate_key(course_copy: Path) -> None:
    path = course_copy / "exercises/basics/bug.yaml"
    path.write_text(path.read_text() + "title: again\n")
    assert "duplicate key 'title'" in only(problems_of(course_copy))


def test_reference_that_raises(course_copy: Path) -> None:
    edit(
        course_copy / "exercises/basics/reference.py",
        "return math.hypot(dx, dy)",
        "return math.hypot(dx, dy) / 0",
    )
    message = only(problems_of(course_copy))
    assert message.startswith(
        "exercises/basics/reference.py:9: distance(dx=3, dy=4) raised ZeroDivisionError"
    )


def test_unsatisfiable_require(course_copy: Path) -> None:
    path = course_copy / "exercises/basics/count.yaml"
    path.write_text(path.read_text() + "require:\n  - n > 100\n")
    assert "canonical parameters fail" in only(problems_of(course_copy))


def test_one_broken_exercise_does_not_hide_the_rest(course_copy: Path) -> None:
    edit(course_copy / "exercises/basics/pick.yaml", "kind: choice", "kind: choise")
    course = load_course(course_copy)
    with pytest.raises(CourseError, match="did you mean 'choice'"):
        course.exercise("basics/pick")
    assert course.exercise("basics/several").kind == "multi"
    assert len(problems_of(course_copy)) == 1


def test_code_examples_must_lie_in_the_declared_domain(course_copy: Path) -> None:
    """Edge examples are part of the stated domain: a value outside it, or text where a number
    is declared (YAML reads ``1.0e6`` as a string), is a path:line problem."""
    path = course_copy / "exercises" / "basics" / "range-bearing.yaml"
    text = path.read_text()
    text = text.replace("  - {dx: 1, dy: 0, theta: 0}", "  - {dx: 100, dy: 0, theta: 0}")
    text = text.replace("  - {dx: -1, dy: 0, theta: 0}", "  - {dx: -1, dy: 1.0e6, theta: 0}")
    path.write_text(text)
    with pytest.raises(CourseError) as caught:
        load_course(course_copy).exercise("basics/range-bearing")
    messages = [str(p) for p in caught.value.problems]
    assert any("range-bearing.yaml:18: example value dx: 100" in m for m in messages), messages
    assert any("'1.0e6' is not a number" in m for m in messages), messages
