"""Each exporter is a pure projection of a grade result, pinned by a golden file.

Regenerate after an intended change: ``UPDATE_GOLDEN=1 pytest tests/batch/test_batch_exporters.py``
and read the diff.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from slamcourse.batch import exporters
from slamcourse.batch.grade import ExerciseGrade, SubmissionGrade
from slamcourse.errors import UsageError

GOLDEN = Path(__file__).parent / "golden"

EXERCISES = (
    ExerciseGrade(
        "basics/distance",
        "A distance",
        "number",
        1,
        12345,
        "passed",
        1.0,
        "Correct.",
        attempts=2,
        command="slamcourse check basics/distance --seed 12345 --answer='5'",
        seconds=0.01,
    ),
    ExerciseGrade(
        "basics/count",
        "A count",
        "number",
        1,
        777,
        "failed",
        0.0,
        "Not quite: 6 is not accepted.\n\nThe robot's own pose belongs to the state too.",
        misconception="forgot-pose",
        attempts=4,
        command="slamcourse check basics/count --seed 777 --answer='6'",
        seconds=0.02,
    ),
    ExerciseGrade(
        "basics/steps",
        "Steps in order",
        "order",
        1,
        0,
        "failed",
        0.5,
        "Half of the steps are in order.",
        attempts=1,
        seconds=0.0,
    ),
    ExerciseGrade(
        "basics/heading",
        "A heading",
        "number",
        1,
        0,
        "missing",
        0.0,
        "No answer was handed in for this exercise.",
    ),
    ExerciseGrade(
        "basics/range-bearing",
        "Write range_bearing",
        "code",
        1,
        0,
        "failed",
        0.0,
        "All 100 test inputs passed, edge cases included.\n\n1 of 1 hidden check failed: "
        "property tests on inputs your local check never drew.",
        hidden={"runs": 1, "failed": 1},
        attempts=3,
        command="slamcourse check basics/range-bearing --file code/basics/range-bearing.py",
        seconds=1.5,
    ),
)
GRADED = SubmissionGrade(
    "ada.zip", "learner-0123456789ab", "graded", EXERCISES, warnings=("a note",), seconds=2.0
)
BROKEN = SubmissionGrade("bob.zip", None, "error", error="bob.zip is not a readable zip")
CASES = {
    "gradescope.json": lambda: exporters.gradescope(GRADED),
    "gradescope-error.json": lambda: exporters.gradescope(BROKEN),
    "exercism.json": lambda: exporters.exercism(GRADED),
    "exercism-error.json": lambda: exporters.exercism(BROKEN),
    "prairielearn.json": lambda: exporters.prairielearn(GRADED),
    "prairielearn-error.json": lambda: exporters.prairielearn(BROKEN),
    "junit.xml": lambda: exporters.junit([GRADED, BROKEN]),
    "gradebook.csv": lambda: exporters.gradebook([GRADED, BROKEN]),
}


def rendered(name: str) -> str:
    value = CASES[name]()
    return value if isinstance(value, str) else json.dumps(value, indent=2) + "\n"


@pytest.mark.parametrize("name", CASES)
def test_golden(name: str) -> None:
    path = GOLDEN / name
    if os.environ.get("UPDATE_GOLDEN"):
        path.write_text(rendered(name), encoding="utf-8")
    assert rendered(name) == path.read_text(encoding="utf-8")


def test_gradescope_follows_the_spec() -> None:
    data = exporters.gradescope(GRADED)
    assert data["score"] == 1.5
    for test in data["tests"]:
        assert set(test) <= {
            "score",
            "max_score",
            "status",
            "name",
            "number",
            "output",
            "output_format",
            "tags",
            "visibility",
            "extra_data",
            "name_format",
        }
        assert test["status"] in ("passed", "failed")
        assert test["visibility"] in ("hidden", "after_due_date", "after_published", "visible")


def test_exercism_follows_version_3() -> None:
    data = exporters.exercism(GRADED)
    assert data["version"] == 3 and data["status"] == "fail"
    for test in data["tests"]:
        assert test["status"] in ("pass", "fail", "error")
        assert (test["status"] == "pass") == ("message" not in test)
        assert isinstance(test["task_id"], int)
    passing = SubmissionGrade("a", "a", "graded", EXERCISES[:1])
    assert exporters.exercism(passing)["status"] == "pass"
    assert exporters.exercism(BROKEN)["message"]


def test_prairielearn_score_is_a_fraction() -> None:
    data = exporters.prairielearn(GRADED)
    assert data["gradable"] is True and 0 <= data["score"] <= 1
    assert data["score"] == pytest.approx(1.5 / 5)
    assert all({"points", "max_points"} <= set(t) for t in data["tests"])
    assert exporters.prairielearn(BROKEN)["gradable"] is False


def test_junit_counts() -> None:
    root = ET.fromstring(exporters.junit([GRADED, BROKEN]))
    assert root.tag == "testsuites"
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("6", "4", "1")


def test_gradebooks_of_shards_merge() -> None:
    other = SubmissionGrade(
        "cy.zip", "learner-cccccccccccc", "graded", EXERCISES[:2] + EXERCISES[2:]
    )
    a = exporters.gradebook([GRADED])
    b = exporters.gradebook([other, BROKEN])
    merged = exporters.merge_gradebooks([a, b])
    assert merged == exporters.gradebook([GRADED, other, BROKEN])
    only_errors = exporters.gradebook([BROKEN])
    assert exporters.merge_gradebooks([only_errors, a]) == exporters.gradebook([GRADED, BROKEN])
    with pytest.raises(UsageError, match="not a slamcourse gradebook"):
        exporters.merge_gradebooks(["a,b\n1,2\n"])


def test_what_a_learner_chose_cannot_break_the_files() -> None:
    tricky = SubmissionGrade(
        "=cmd.zip", "=HYPERLINK(\"x\")", "graded",
        (ExerciseGrade("basics/a", "A", "number", 1, 0, "failed", 0.0, "got \x1b[31m\x00"),),
    )  # fmt: skip
    root = ET.fromstring(exporters.junit([tricky]))  # well-formed despite control characters
    assert root.find("testsuite").get("name") == '=HYPERLINK("x")'  # type: ignore[union-attr]
    row = exporters.gradebook([tricky]).splitlines()[1]
    assert row.startswith('"\'=HYPERLINK(""x"")",\'=cmd.zip,')
