"""A code exercise's own sandbox ``limits:``: parsed with path:line problems, and applied to the
worker that grades the learner's file (instead of the engine's default-limits worker)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from slamcourse.course.loader import load_course
from slamcourse.grading.pool import WorkerPool
from slamcourse.kinds import get_kind
from slamcourse.sandbox import Limits
from slamcourse.validate import validate_course
from slamcourse.verdict import Verdict

YAML = "exercises/basics/range-bearing.yaml"

# sleeps on the first fixed example (dx=1, dy=0) only, then answers correctly
SLEEPER = """
import math, time
def range_bearing(dx, dy, theta):
    if dx == 1 and dy == 0:
        time.sleep({seconds})
    return math.hypot(dx, dy), math.atan2(dy, dx) - theta
"""


def with_limits(course: Path, text: str) -> Path:
    path = course / YAML
    path.write_text(path.read_text() + text)
    return course


def grade(course: Path, source: str, spawn: Any = None) -> Verdict:
    spec = load_course(course).exercise("basics/range-bearing")
    return get_kind("code").check_source(  # type: ignore[attr-defined]
        spec, source, "attempt.py", spawn=spawn
    )


def problems(course: Path) -> list[str]:
    report = validate_course(course, variants_per_exercise=1, min_mutants=0, min_variants=0)
    return [str(p) for p in report.problems if "limit" in p.message]


def test_limits_parse_into_sandbox_limits(course_copy: Path) -> None:
    with_limits(course_copy, "limits: {call_seconds: 90, total_seconds: 240, cpu_seconds: 240}\n")
    opts = load_course(course_copy).exercise("basics/range-bearing").options
    assert opts.sandbox_limits() == Limits(call_seconds=90, total_seconds=240, cpu_seconds=240)


def test_no_limits_means_the_defaults(course_copy: Path) -> None:
    opts = load_course(course_copy).exercise("basics/range-bearing").options
    assert opts.limits == ()
    assert opts.sandbox_limits() is None


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("limits: {wall_seconds: 10}\n", "unknown key 'wall_seconds' in 'limits'"),
        ("limits: {call_seconds: 1000}\n", "'call_seconds' must be above 0 and at most 120"),
        ("limits: {total_seconds: 0}\n", "'total_seconds' must be above 0 and at most 300"),
        ("limits: {cpu_seconds: 2.5}\n", "'cpu_seconds' must be a whole number"),
        ("limits: {memory_bytes: 8589934592}\n", "at most 4294967296 (4 GiB)"),
        ("limits: {call_seconds: 1.0e6}\n", "YAML reads '1.0e6' as text"),
        ("limits: 10\n", "'limits' must be a mapping"),
    ],
)
def test_bad_limits_are_reported_at_their_line(course_copy: Path, text: str, words: str) -> None:
    lines = (course_copy / YAML).read_text().count("\n")
    with_limits(course_copy, text)
    found = problems(course_copy)
    assert len(found) == 1, found
    assert found[0].startswith(f"{YAML}:{lines + 1}: "), found
    assert words in found[0], found


def test_the_exercise_limits_replace_the_engine_worker(course_copy: Path) -> None:
    """A lower call limit times out a 1.5 s call that the defaults allow: the engine's worker
    factory is asked for the exercise's limits, and its pool (whose ready worker has the
    default limits) starts a worker with them instead."""
    asked: list[Any] = []
    pool = WorkerPool()  # the engine's: default limits, one worker started early
    pool.warm()

    def engine_worker(limits: Any, scipy: bool) -> Any:
        asked.append(limits)
        return pool.take(limits, scipy=scipy)

    source = SLEEPER.format(seconds=1.5)
    with_limits(course_copy, "limits: {call_seconds: 1}\n")
    try:
        verdict = grade(course_copy, source, spawn=engine_worker)
    finally:
        pool.close()
    assert asked == [Limits(call_seconds=1)]
    assert verdict.status == "timeout", verdict.feedback  # the default 5 s would have passed
    assert "range_bearing(dx=1" in verdict.feedback


@pytest.mark.slow
def test_a_call_beyond_the_default_limit_passes_within_the_exercise_limit(
    course_copy: Path, tmp_path: Path
) -> None:
    source = SLEEPER.format(seconds=5.5)
    assert grade(course_copy, source).status == "timeout"  # the default: 5 s per call
    with_limits(course_copy, "limits: {call_seconds: 10}\n")
    verdict = grade(course_copy, source)
    assert verdict.status == "passed", verdict.feedback
