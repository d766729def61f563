"""Handed-in notebooks read by the batch grader without running them: which cell answers
what, who ran it, and what a notebook may not claim."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path
from typing import Any

import pytest

from slamcourse.batch.grade import GradeOptions, grade_submission
from slamcourse.batch.notebooks import NotebookAnswers, NotebookError, read_notebook
from slamcourse.batch.submission import SubmissionError, course_hash, learner_id, read
from tests.batch.conftest import make_submission, right_answer
from tests.conftest import FIXTURE_COURSE

SEED = 4242


def identity(seed: int = SEED) -> dict[str, Any]:
    return {
        "learner": {"id": learner_id(seed), "name": None, "seed": seed},
        "course": {"version": "custom", "hash": course_hash(FIXTURE_COURSE)},
        "engine": "0.1.0",
    }


def cell(source: str, record: dict[str, Any] | None = None) -> dict[str, Any]:
    outputs = []
    if record is not None:
        outputs.append(
            {
                "output_type": "execute_result",
                "execution_count": 1,
                "data": {"text/plain": "…"},
                "metadata": {"slamcourse": record},
            }
        )
    return {"cell_type": "code", "source": source, "metadata": {}, "outputs": outputs}


def notebook(*cells: dict[str, Any]) -> bytes:
    return json.dumps({"cells": list(cells), "metadata": {}, "nbformat": 4}).encode()


def test_which_cell_answers_what() -> None:
    found = NotebookAnswers()
    data = notebook(
        cell('progress("basics")', identity()),
        cell('check("basics/count", "3")\ncheck("basics/distance", "")'),
        cell(
            'check("basics/count", 49 + 2)',
            {**identity(), "exercise": "basics/count", "answer": "51"},
        ),
        cell('x = 2\ncheck("basics/heading", pi / x)'),  # never run: its source text
        cell("%%slamcourse check basics/range-bearing\nimport math\n"),
        cell(
            'check("basics/range-bearing", f)',
            {"exercise": "basics/range-bearing", "source": "def range_bearing(): pass\n"},
        ),
        {"cell_type": "markdown", "source": 'check("basics/offset", "[1, 2]")', "metadata": {}},
    )
    read_notebook("ch.ipynb", data, found)
    assert found.text == {
        "basics/count": ("51", "ch.ipynb, cell 3"),  # the last answer in cell order
        "basics/heading": ("pi / x", "ch.ipynb, cell 4"),
    }
    assert found.code == {
        "basics/range-bearing": ("def range_bearing(): pass\n", "ch.ipynb, cell 6"),
    }
    assert found.identities["ch.ipynb"]["learner"]["seed"] == SEED
    with pytest.raises(NotebookError, match="answered in two notebooks"):
        read_notebook("other.ipynb", notebook(cell('check("basics/count", "2")')), found)
    with pytest.raises(NotebookError, match="not a notebook"):
        read_notebook("bad.ipynb", b"{not json", NotebookAnswers())
    mixed = notebook(cell("1", identity(1)), cell("2", identity(2)))
    with pytest.raises(NotebookError, match="2 learners"):
        read_notebook("mixed.ipynb", mixed, NotebookAnswers())


def test_notebooks_beside_a_manifest(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "ada", SEED, {"basics/count": "1", "basics/heading": "2"})
    right = right_answer(SEED, "basics/count")
    (sub / "basics.ipynb").write_text(
        notebook(cell("progress()", identity()), cell(f'check("basics/count", "{right}")')).decode()
    )
    read_back = read(sub)
    assert any("basics/count is answered both" in n for n in read_back.notes)
    graded = grade_submission(sub, GradeOptions(course=FIXTURE_COURSE))
    by_id = {e.exercise: e for e in graded.exercises}
    assert by_id["basics/count"].status == "passed"  # the notebook's answer
    assert by_id["basics/heading"].status == "failed"  # the manifest's, still graded
    assert any("answered both" in w for w in graded.warnings)
    (sub / "basics.ipynb").write_text(notebook(cell("progress()", identity(SEED + 1))).decode())
    with pytest.raises(SubmissionError, match="another learner"):
        read(sub)


def test_a_zip_of_notebooks_and_claims_checked(tmp_path: Path) -> None:
    right = right_answer(SEED, "basics/distance")
    data = notebook(cell(f'check("basics/distance", "{right}")', identity()))
    archive = tmp_path / "bob.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        zf.writestr("bob/01-basics.ipynb", data)
    graded = grade_submission(archive, GradeOptions(course=FIXTURE_COURSE))
    assert graded.status == "graded" and graded.learner == learner_id(SEED)
    assert {e.exercise: e.status for e in graded.exercises}["basics/distance"] == "passed"
    forged = identity()
    forged["learner"]["id"] = "learner-000000000000"
    (tmp_path / "eve").mkdir()
    (tmp_path / "eve" / "a.ipynb").write_bytes(notebook(cell('check("basics/count", "1")', forged)))
    refused = grade_submission(tmp_path / "eve", GradeOptions(course=FIXTURE_COURSE))
    assert refused.status == "error" and "does not belong to learner.seed" in (refused.error or "")
    other = identity()
    other["course"]["hash"] = "sha256:" + "0" * 64
    (tmp_path / "old").mkdir()
    (tmp_path / "old" / "a.ipynb").write_bytes(notebook(cell("progress()", other)))
    refused = grade_submission(tmp_path / "old", GradeOptions(course=FIXTURE_COURSE))
    assert refused.status == "error" and "not the course this grader has" in (refused.error or "")
