"""A generated notebook run end to end by nbclient on a real IPython kernel: a right and a wrong
answer, a right and a wrong function, progress shared with the CLI; then the saved notebook
handed in and graded by the batch grader exactly as the same answers in a manifest."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import nbformat
import pytest
from nbclient import NotebookClient

from slamcourse.batch.grade import GradeOptions, grade_submission
from slamcourse.cli import main
from slamcourse.engine import Engine
from slamcourse.notebook.export import export_notebooks
from tests.batch.conftest import make_submission
from tests.conftest import FIXTURE_COURSE
from tests.notebook.conftest import CODE_ID, SOLUTION, WRONG_SOLUTION, right_answer

pytestmark = pytest.mark.slow


def _answer_cell(nb: Any, exercise_id: str) -> Any:
    return next(
        c
        for c in nb.cells
        if c.metadata.get("slamcourse") == {"exercise": exercise_id, "role": "answer"}
    )


def _result(cell: Any) -> tuple[str, dict[str, Any]]:
    """The text and slamcourse metadata of a cell's one displayed result."""
    outs = [o for o in cell.outputs if o.output_type in ("execute_result", "display_data")]
    errors = [o for o in cell.outputs if o.output_type == "error"]
    assert not errors, errors
    assert len(outs) == 1, cell.outputs
    return outs[0].data["text/plain"], outs[0].metadata["slamcourse"]


def _statuses(capsys: pytest.CaptureFixture[str]) -> dict[str, dict[str, Any]]:
    capsys.readouterr()
    assert main(["list", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    return {ex["id"]: ex for ch in data for ex in ch["exercises"]}


@pytest.fixture(scope="module")
def kernel_name() -> str:
    from jupyter_client.kernelspec import KernelSpecManager

    specs = KernelSpecManager().find_kernel_specs()
    assert "python3" in specs, f"no python3 kernel (ipykernel missing?): {specs}"
    return "python3"


def test_notebook_end_to_end_then_graded(
    course_env: Path, tmp_path: Path, kernel_name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with Engine.open() as engine:
        seed = engine.progress.learner_seed  # type: ignore[union-attr]
        distance = right_answer(engine, "basics/distance")
        pick = engine.exercise("basics/pick")
        shown = engine.pose("basics/pick").form["options"]
    right_pick = next(o["id"] for o in shown if o["text"].startswith("A pose graph"))
    assert pick.kind == "choice"
    # the terminal solves one exercise first: the notebook's progress must show it
    assert main(["check", "basics/pick", "--answer", right_pick]) == 0

    folder = tmp_path / "notebooks"
    path = export_notebooks(None, folder)[0]
    nb = nbformat.read(str(path), as_version=4)
    _answer_cell(nb, "basics/distance").source = f'check("basics/distance", "{distance}")'
    _answer_cell(nb, "basics/count").source = 'answer = 1\ncheck("basics/count", answer)'
    code = _answer_cell(nb, CODE_ID)
    code.source = f"%%slamcourse check {CODE_ID}\n{SOLUTION}"
    # a wrong function first, defined in the notebook and checked by the function itself
    wrong = nbformat.v4.new_code_cell(
        WRONG_SOLUTION.replace("range_bearing", "first_try") + f'\ncheck("{CODE_ID}", first_try)'
    )
    nb.cells.insert(nb.cells.index(code), wrong)
    use = nbformat.v4.new_code_cell("print(range_bearing(3.0, 4.0, 0.0)[0])")
    nb.cells.insert(nb.cells.index(code) + 1, use)  # the checked cell is defined here too
    NotebookClient(
        nb, timeout=180, kernel_name=kernel_name, resources={"metadata": {"path": str(folder)}}
    ).execute()

    progress_text, who = _result(nb.cells[1])
    assert "✓ basics/pick" in progress_text and "1/15 solved" in progress_text
    assert who["learner"]["seed"] == seed
    text, meta = _result(_answer_cell(nb, "basics/distance"))
    assert meta["status"] == "passed" and text.startswith("✓ Correct")
    text, meta = _result(_answer_cell(nb, "basics/count"))
    assert meta["status"] == "failed" and meta["answer"] == "1"
    text, meta = _result(wrong)
    assert meta["status"] == "failed" and "first_try" in meta["source"]
    text, meta = _result(code)
    assert meta["status"] == "passed" and "basics/range-bearing: solved" in text
    assert [o.get("text") for o in use.outputs] == ["5.0\n"]
    # the kernel's answers are in the terminal's progress store
    states = _statuses(capsys)
    assert states["basics/distance"]["status"] == "solved"
    assert states[CODE_ID]["status"] == "solved" and states[CODE_ID]["attempts"] == 2
    assert states["basics/count"]["status"] == "pending"
    assert states["basics/count"]["attempts"] == 1

    # handed in: the saved notebook alone, and the same answers as a manifest
    handed = tmp_path / "ada"
    handed.mkdir()
    nbformat.write(nb, str(handed / path.name))
    options = GradeOptions(course=FIXTURE_COURSE)
    graded = grade_submission(handed, options)
    assert graded.status == "graded", graded.error
    by_id = {e.exercise: e for e in graded.exercises}
    manifest = make_submission(
        tmp_path / "ada-manifest",
        seed,
        {"basics/distance": distance, "basics/count": "1"},
        SOLUTION,
    )
    reference = {e.exercise: e for e in grade_submission(manifest, options).exercises}
    for ex in ("basics/distance", "basics/count", CODE_ID):
        mine, theirs = by_id[ex].to_dict(), reference[ex].to_dict()
        for key in ("status", "score", "feedback", "variant", "misconception", "tests"):
            assert mine[key] == theirs[key], (ex, key)
    assert by_id["basics/distance"].status == "passed"
    assert by_id["basics/count"].status == "failed"
    assert by_id[CODE_ID].status == "passed"
    assert by_id["basics/pick"].status == "missing"  # answered in the terminal, not here
    # a notebook file on its own is a submission too
    single = grade_submission(handed / path.name, options)
    assert single.status == "graded" and single.score == graded.score

    # a notebook never run says nothing of who ran it
    blank = tmp_path / "blank"
    blank.mkdir()
    shutil.copy(path, blank / path.name)
    refused = grade_submission(blank, options)
    assert refused.status == "error" and "first code cell" in (refused.error or "")
