"""Code exercises on the fixture course: every verdict the grader can give, through the sandbox."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from slamcourse.cli import main
from slamcourse.course.loader import load_course
from slamcourse.kinds import get_kind
from slamcourse.verdict import Verdict
from tests.conftest import FIXTURE_COURSE

COURSE = load_course(FIXTURE_COURSE)
SPEC = COURSE.exercise("basics/range-bearing")


def grade(source: str) -> Verdict:
    return get_kind("code").check_source(SPEC, source, "attempt.py")  # type: ignore[attr-defined]


CORRECT = {
    "math.hypot, unwrapped": """
import math
def range_bearing(dx, dy, theta):
    return math.hypot(dx, dy), math.atan2(dy, dx) - theta
""",
    "numpy array, wrapped": """
import numpy as np
def range_bearing(a, b, c):
    phi = np.arctan2(b, a) - c
    return np.array([np.sqrt(a * a + b * b), (phi + np.pi) % (2 * np.pi) - np.pi])
""",
    "list, pure python": """
def range_bearing(dx, dy, theta):
    import cmath
    z = complex(dx, dy)
    return [abs(z), cmath.phase(z) - theta + 4 * cmath.pi]
""",
}


@pytest.mark.parametrize("source", CORRECT.values(), ids=CORRECT.keys())
def test_correct_implementations_pass(source: str) -> None:
    verdict = grade(source)
    assert verdict.status == "passed", verdict.feedback
    assert verdict.details["examples"] >= 100


@pytest.mark.parametrize(
    ("source", "misconception", "words"),
    [
        (
            "import math\ndef range_bearing(dx, dy, theta):\n"
            "    return dx*dx + dy*dy, math.atan2(dy, dx) - theta\n",
            "squared",
            "square root",
        ),
        (
            "import math\ndef range_bearing(dx, dy, theta):\n"
            "    return math.hypot(dx, dy), math.atan2(dy, dx)\n",
            "no-heading",
            "subtract theta",
        ),
        (
            "import math\ndef range_bearing(dx, dy, theta):\n"
            "    return math.hypot(dx, dy), math.atan(dy / dx) - theta\n",
            None,
            "expected",
        ),
    ],
)
def test_wrong_implementations_fail_with_minimal_input(
    source: str, misconception: str | None, words: str
) -> None:
    verdict = grade(source)
    assert verdict.status == "failed"
    assert verdict.misconception == misconception
    assert words in verdict.feedback
    # the input is either one of the fixed edge cases or the one Hypothesis shrank to
    assert ("shrank the failure to this small input" in verdict.feedback) != (
        "fixed edge cases" in verdict.feedback
    )
    assert set(verdict.details["input"]) == {"dx", "dy", "theta"}


def test_learner_traceback_is_trimmed_to_their_file() -> None:
    verdict = grade(
        "def helper(x):\n    return 1 / x\n\ndef range_bearing(dx, dy, theta):\n"
        "    return helper(0), 0\n"
    )
    assert verdict.status == "failed"
    assert "ZeroDivisionError" in verdict.feedback
    assert "- `attempt.py:2`: `return 1 / x`" in verdict.feedback
    assert "attempt.py:5" in verdict.feedback
    assert "slamcourse" not in verdict.feedback and "site-packages" not in verdict.feedback


@pytest.mark.parametrize(
    ("source", "status", "words"),
    [
        ("def range_bearing(dx, dy, theta)\n    return 1, 2\n", "invalid", "attempt.py:1: syntax"),
        ("def other(dx, dy, theta):\n    return 1, 2\n", "invalid", "defines other"),
        ("def range_bearing(dx, dy):\n    return 1, 2\n", "invalid", "3 parameters"),
        ("range_bearing = 3\n", "invalid", "not a function"),
        ("raise ValueError('at import')\n", "failed", "raised while it was loaded"),
        ("def range_bearing(dx, dy, theta):\n    while True:\n        pass\n", "timeout", "loop"),
        (
            "import sys\ndef range_bearing(dx, dy, theta):\n    sys.exit(0)\n",
            "failed",
            "stopped the grader's worker",
        ),
        ("def range_bearing(dx, dy, theta):\n    return {'r': 1}\n", "failed", "unsupported"),
        (
            "def range_bearing(dx, dy, theta):\n    return float('nan'), 0.0\n",
            "failed",
            "not a finite number",
        ),
        (
            "def range_bearing(dx, dy, theta):\n    print('PASSED')\n    return None\n",
            "failed",
            "forget to return",
        ),
    ],
)
def test_every_outcome_is_a_verdict(source: str, status: str, words: str) -> None:
    verdict = grade(source)
    assert verdict.status == status, verdict.feedback
    assert words in verdict.feedback


def test_grading_is_deterministic() -> None:
    source = (
        "import math\ndef range_bearing(dx, dy, theta):\n"
        "    return math.hypot(dx, dy) + (0.1 if dx > 7 else 0), math.atan2(dy, dx) - theta\n"
    )
    first, second = grade(source), grade(source)
    assert first.status == second.status == "failed"
    assert first.details["input"] == second.details["input"]
    assert first.details["seed"] == second.details["seed"]


def test_cli_check_file_and_workspace(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, private_home: Path
) -> None:
    course = ["--course", str(FIXTURE_COURSE)]
    attempt = tmp_path / "mine.py"
    attempt.write_text(CORRECT["math.hypot, unwrapped"])
    assert main([*course, "check", "basics/range-bearing", "--file", str(attempt), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"]["status"] == "passed" and data["file"] == str(attempt)
    # no file yet: `check ID` writes the starter into the workspace and grades it
    assert main([*course, "check", "basics/range-bearing"]) == 1
    assert "NotImplementedError" in capsys.readouterr().out
    assert (private_home / "workspace" / "basics" / "range_bearing.py").is_file()
    assert main([*course, "check", "basics/range-bearing", "--answer", "5"]) == 2
    assert main([*course, "check", "basics/distance", "--file", str(attempt)]) == 2
    capsys.readouterr()


def test_validator_runs_solution_starter_and_misconceptions(course_copy: Path) -> None:
    from slamcourse.validate import validate_exercise

    course = load_course(course_copy)
    none = {"min_mutants": 0, "min_variants": 0}
    assert validate_exercise(course, "basics/range-bearing", 1, **none) == []
    solution = course_copy / "exercises/basics/solutions/range_bearing.py"
    solution.write_text(solution.read_text().replace("math.hypot(dx, dy)", "dx"))
    ref = course_copy / "exercises/basics/reference.py"
    ref.write_text(
        ref.read_text().replace(
            "return (math.hypot(dx, dy), math.atan2(dy, dx))", "return range_bearing(dx, dy, theta)"
        )
    )
    problems = [
        str(p)
        for p in validate_exercise(load_course(course_copy), "basics/range-bearing", 1, **none)
    ]
    assert any("the solution range_bearing.py fails" in p for p in problems), problems
    assert any("misconception 'no-heading' passes every test input" in p for p in problems)


def test_require_isolation_without_namespaces_is_an_error_verdict(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SLAMCOURSE_SANDBOX", "rlimits")
    attempt = tmp_path / "mine.py"
    attempt.write_text(CORRECT["math.hypot, unwrapped"])
    code = main(
        [
            "--course",
            str(FIXTURE_COURSE),
            "check",
            "basics/range-bearing",
            "--file",
            str(attempt),
            "--require-isolation",
            "--json",
        ]
    )
    verdict = json.loads(capsys.readouterr().out)["verdict"]
    assert code == 3
    assert verdict["status"] == "error" and "grader" in verdict["feedback"]
    # without the requirement the fallback grades, and says so
    assert (
        main(
            [
                "--course",
                str(FIXTURE_COURSE),
                "check",
                "basics/range-bearing",
                "--file",
                str(attempt),
                "--json",
            ]
        )
        == 0
    )
    assert json.loads(capsys.readouterr().out)["verdict"]["details"]["isolation"] == "rlimits"


def test_doctor_reports_isolation(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["doctor", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["isolation"] in ("namespaces", "rlimits") and info["isolation_reason"]


def test_replayed_recording_gives_the_same_verdicts(private_home: Path, course_copy: Path) -> None:
    """After a passing run, checks replay the recorded inputs; verdicts do not change."""
    from slamcourse.grading import replay, testset
    from slamcourse.grading.properties import exercise_seed

    (course_copy / "exercises/basics/recordings/range-bearing.json").unlink()  # none shipped
    spec = load_course(course_copy).exercise(SPEC.id)

    def grade(source: str) -> Verdict:
        return get_kind("code").check_source(spec, source, "attempt.py")  # type: ignore[attr-defined,no-any-return]

    key = replay.recording_key(spec, exercise_seed(spec.id), spec.options.max_examples)
    assert replay.load(key) is None
    first = grade(CORRECT["math.hypot, unwrapped"])  # full Hypothesis run, then recorded
    inputs = replay.load(key)
    # the cache holds the drawn inputs (the examples first); the check also ran the boundary
    # inputs derived from them, each distinct input once: the test set now built from the cache
    tests = testset.build(spec)
    assert inputs is not None and tests.recorded
    keys = [testset.input_key(c.kwargs) for c in tests.cases]
    assert {testset.input_key(i) for i in inputs} <= set(keys)
    assert any(c.origin.startswith("boundary") for c in tests.cases)
    assert len(keys) == first.details["examples"]
    second = grade(CORRECT["numpy array, wrapped"])  # replayed
    assert second.to_dict() == {**first.to_dict(), "feedback": second.feedback}
    assert second.details["examples"] == first.details["examples"]
    wrong = (
        "import math\ndef range_bearing(dx, dy, theta):\n"
        "    return math.hypot(dx, dy) + (0.1 if dx > 7 else 0), math.atan2(dy, dx) - theta\n"
    )
    replayed_failure = grade(wrong)  # fails on a replayed input -> the full run decides
    (private_home / "cache").rename(private_home / "cache-moved")
    fresh_failure = grade(wrong)  # no recording at all
    assert replayed_failure.to_dict() == fresh_failure.to_dict()
    assert replayed_failure.status == "failed"


def test_a_broken_recording_is_ignored(private_home: Path, course_copy: Path) -> None:
    from slamcourse.grading import replay
    from slamcourse.grading.properties import exercise_seed

    shipped = course_copy / "exercises/basics/recordings/range-bearing.json"
    shipped.write_text("{not json")
    spec = load_course(course_copy).exercise(SPEC.id)
    key = replay.recording_key(spec, exercise_seed(spec.id), spec.options.max_examples)
    path = private_home / "cache" / "inputs" / f"{key}.json"
    path.parent.mkdir(parents=True)
    path.write_text("{not json")
    verdict = get_kind("code").check_source(  # type: ignore[attr-defined]
        spec, CORRECT["math.hypot, unwrapped"], "a.py"
    )
    assert verdict.status == "passed"
