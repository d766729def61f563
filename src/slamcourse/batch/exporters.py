"""Grade results in the formats grading platforms read: pure projections of
:class:`~slamcourse.batch.grade.SubmissionGrade`, pinned by golden files (tests/batch/golden/).

| format | file | spec |
|---|---|---|
| Gradescope | ``results.json`` | gradescope-autograders.readthedocs.io, specs |
| Exercism | ``results.json`` (version 3) | exercism/docs, building/tooling/test-runners/interface |
| PrairieLearn | ``results.json`` | PrairieLearn docs, externalGrading |
| JUnit | ``junit.xml`` | testsuites / testsuite / testcase / failure, error |
| gradebook | CSV | one row per learner, one column per exercise, then the total |

A ``missing`` exercise is a failed test whose message says nothing was handed in; a submission
that could not be graded is an ``error`` in each platform's own terms.
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Callable, Sequence
from typing import Any
from xml.etree import ElementTree as ET

from slamcourse.batch.grade import ExerciseGrade, SubmissionGrade
from slamcourse.errors import UsageError

EXERCISM_OUTPUT_MAX = 500
EXERCISM_MESSAGE_MAX = 65535


def _name(e: ExerciseGrade) -> str:
    return f"{e.exercise}: {e.title}"


def _num(x: float) -> float | int:
    """Whole scores as integers (``1``, not ``1.0``), others rounded to 6 places."""
    r = round(x, 6)
    return int(r) if r == int(r) else r


def _message(e: ExerciseGrade) -> str:
    label = {"missing": "not handed in", "invalid": "unreadable"}.get(e.status, e.status)
    return f"{label}: {e.feedback}" if e.status != "passed" else e.feedback


def gradescope(g: SubmissionGrade) -> dict[str, Any]:
    """Gradescope ``results.json``: top-level score, one test per exercise (Markdown output)."""
    if g.status == "error":
        return {
            "score": 0,
            "output": f"This submission could not be graded: {g.error}",
            "output_format": "md",
            "tests": [],
        }
    out: dict[str, Any] = {
        "score": _num(g.score),
        "output": _summary(g),
        "output_format": "md",
        "test_output_format": "md",
        "tests": [
            {
                "name": _name(e),
                "number": str(i),
                "score": _num(e.score),
                "max_score": _num(e.max_score),
                "status": "passed" if e.passed else "failed",
                "visibility": "visible",
                "output": _message(e),
                "tags": [e.kind] + ([e.misconception] if e.misconception else []),
            }
            for i, e in enumerate(g.exercises, start=1)
        ],
    }
    return out


def _summary(g: SubmissionGrade) -> str:
    solved = sum(e.passed for e in g.exercises)
    lines = [
        f"{solved} of {len(g.exercises)} exercises passed: {_num(g.score)} / "
        f"{_num(g.max_score)} points."
    ]
    lines += [f"- note: {w}" for w in g.warnings]
    return "\n".join(lines)


def exercism(g: SubmissionGrade) -> dict[str, Any]:
    """Exercism test-runner ``results.json``, version 3 (``task_id`` = chapter number)."""
    if g.status == "error":
        return {
            "version": 3,
            "status": "error",
            "message": f"This submission could not be graded: {g.error}"[:EXERCISM_MESSAGE_MAX],
        }
    tests = []
    for e in g.exercises:
        test: dict[str, Any] = {
            "name": _name(e),
            "status": "pass" if e.passed else ("error" if e.status == "error" else "fail"),
            "test_code": e.command or f"slamcourse show {e.exercise}",
            "task_id": e.chapter,
        }
        if not e.passed:
            test["message"] = _message(e)[:EXERCISM_MESSAGE_MAX]
        tests.append(test)
    return {
        "version": 3,
        "status": "pass" if all(e.passed for e in g.exercises) else "fail",
        "tests": tests,
    }


def prairielearn(g: SubmissionGrade) -> dict[str, Any]:
    """PrairieLearn external-grader ``results.json``: score in [0, 1], points per test."""
    if g.status == "error":
        return {
            "gradable": False,
            "format_errors": [str(g.error)],
            "message": "This submission could not be graded.",
        }
    return {
        "gradable": True,
        "score": _num(g.score / g.max_score) if g.max_score else 0,
        "message": _summary(g),
        "tests": [
            {
                "name": e.exercise,
                "description": e.title,
                "points": _num(e.score),
                "max_points": _num(e.max_score),
                "message": _message(e),
            }
            for e in g.exercises
        ],
    }


_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _xml(text: str) -> str:
    """Text XML 1.0 can hold: characters it forbids (control characters, lone surrogates)
    become U+FFFD."""
    return _NOT_XML.sub("\ufffd", text)


def junit(grades: Sequence[SubmissionGrade]) -> str:
    """JUnit XML: one ``testsuite`` per submission, one ``testcase`` per exercise."""
    root = ET.Element("testsuites", name="slamcourse")
    totals = {"tests": 0, "failures": 0, "errors": 0}
    for g in grades:
        who = _xml(g.learner or g.submission)
        suite = ET.SubElement(root, "testsuite", name=who)
        counts = {"tests": 0, "failures": 0, "errors": 0}
        if g.status == "error":
            case = ET.SubElement(suite, "testcase", classname=who, name="submission")
            ET.SubElement(case, "error", message="not graded", type="submission").text = _xml(
                str(g.error)
            )
            counts["tests"], counts["errors"] = 1, 1
        for e in g.exercises:
            case = ET.SubElement(suite, "testcase", classname=who, name=e.exercise)
            counts["tests"] += 1
            if e.status == "error":
                counts["errors"] += 1
                ET.SubElement(case, "error", message=e.status, type=e.status).text = _xml(
                    e.feedback
                )
            elif not e.passed:
                counts["failures"] += 1
                ET.SubElement(case, "failure", message=e.status, type=e.status).text = _xml(
                    e.feedback
                )
        for key, value in counts.items():
            suite.set(key, str(value))
            totals[key] += value
    for key, value in totals.items():
        root.set(key, str(value))
    ET.indent(root)
    return '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(root, "unicode") + "\n"


# ------------------------------------------------------------------------------ gradebook

_TAIL = ("total", "max_score", "status", "error")


def gradebook(grades: Sequence[SubmissionGrade]) -> str:
    """CSV: ``learner``, ``submission``, one column per exercise (course order), ``total``,
    ``max_score``, ``status``, ``error``; one row per submission, sorted by learner."""
    exercises: list[str] = []
    for g in grades:
        for e in g.exercises:
            if e.exercise not in exercises:
                exercises.append(e.exercise)
    header = ["learner", "submission", *exercises, *_TAIL]
    rows = []
    for g in grades:
        scores = {e.exercise: _num(e.score) for e in g.exercises}
        rows.append(
            [
                g.learner or "",
                g.submission,
                *(scores.get(ex, "") for ex in exercises),
                _num(g.score) if g.status == "graded" else "",
                _num(g.max_score) if g.status == "graded" else "",
                g.status,
                g.error or "",
            ]
        )
    return _csv(header, sorted(rows, key=lambda r: (str(r[0]), str(r[1]))))


def _csv(header: Sequence[Any], rows: Sequence[Sequence[Any]]) -> str:
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    writer.writerows([[_cell(v) for v in row] for row in rows])
    return buf.getvalue()


def _cell(value: Any) -> Any:
    """A text cell a spreadsheet would read as a formula (``=``, ``+``, ``-``, ``@``) gets a
    leading ``'``: a learner's name or an error message never runs in the gradebook."""
    if isinstance(value, str) and value[:1] in ("=", "+", "-", "@", "\t", "\r"):
        return "'" + value
    return value


def merge_gradebooks(texts: Sequence[str]) -> str:
    """Shards' gradebooks as one: the same columns (a shard with only errored submissions has
    no exercise columns and takes the others'), rows of all, sorted by learner."""
    header: list[str] | None = None
    rows: list[dict[str, str]] = []
    for text in texts:
        reader = csv.DictReader(io.StringIO(text))
        fields = list(reader.fieldnames or [])
        if fields[:2] != ["learner", "submission"] or tuple(fields[-4:]) != _TAIL:
            raise UsageError("--merge-csv: a file is not a slamcourse gradebook")
        if header is None or len(fields) > len(header):
            if header is not None and len(header) > 6 and fields != header:
                raise UsageError("--merge-csv: the gradebooks have different exercise columns")
            header = fields
        elif len(fields) > 6 and fields != header:
            raise UsageError("--merge-csv: the gradebooks have different exercise columns")
        rows.extend(reader)
    if header is None:
        raise UsageError("--merge-csv needs at least one gradebook")
    out = [[row.get(col) or "" for col in header] for row in rows]
    return _csv(header, sorted(out, key=lambda r: (r[0], r[1])))


PER_SUBMISSION: dict[str, Callable[[SubmissionGrade], dict[str, Any]]] = {
    "gradescope": gradescope,
    "exercism": exercism,
    "prairielearn": prairielearn,
    "json": SubmissionGrade.to_dict,
}
FORMATS = (*PER_SUBMISSION, "junit")
