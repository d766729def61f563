"""Class statistics, the Gradescope bundle and the PrairieLearn entry point."""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from slamcourse.batch import stats
from slamcourse.batch.bundle import gradescope_bundle
from slamcourse.batch.grade import SubmissionGrade
from slamcourse.batch.prairielearn import grade_job
from slamcourse.cli import main
from slamcourse.errors import UsageError
from tests.batch.conftest import make_submission, right_answer
from tests.batch.test_batch_exporters import BROKEN, EXERCISES, GRADED
from tests.conftest import FIXTURE_COURSE


def test_statistics_per_exercise(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    second = SubmissionGrade("cy.zip", "cy", "graded", EXERCISES[:1] + EXERCISES[1:2])
    results = tmp_path / "results"
    results.mkdir()
    for g in (GRADED, second, BROKEN):
        (results / f"{g.submission}.json").write_text(json.dumps(g.to_dict()))
    data = stats.statistics(stats.load_results([results]))
    assert (data["submissions"], data["graded"], data["errors"]) == (3, 2, 1)
    rows = {r["exercise"]: r for r in data["exercises"]}
    assert rows["basics/distance"]["solve_rate"] == 1.0
    assert rows["basics/count"]["mean_attempts"] == 4
    assert rows["basics/count"]["misconceptions"] == [["forgot-pose", 2]]
    assert (
        rows["basics/heading"]["answered"] == 0 and rows["basics/heading"]["mean_attempts"] is None
    )
    assert rows["basics/distance"]["histogram"] == {"2": 2}
    assert main(["stats", str(results)]) == 0
    text = capsys.readouterr().out
    assert "solved 0/2 (0%)" in text and "forgot-pose ×2" in text and "█" in text
    (tmp_path / "junk.json").write_text("[1]")
    with pytest.raises(UsageError, match="not a slamcourse grade result"):
        stats.load_results([tmp_path / "junk.json"])


def test_gradescope_bundle(tmp_path: Path) -> None:
    wheel = tmp_path / "slamcourse-0.1.0-py3-none-any.whl"
    wheel.write_bytes(b"wheel")
    out = gradescope_bundle(
        tmp_path / "b.zip", wheel=str(wheel), course=str(FIXTURE_COURSE), secret="s3"
    )
    with zipfile.ZipFile(out) as zf:
        names = set(zf.namelist())
        assert {"setup.sh", "run_autograder", wheel.name, "secret"} <= names
        assert "course/exercises/basics/reference.py" in names
        for script in ("setup.sh", "run_autograder"):
            assert stat.S_IMODE(zf.getinfo(script).external_attr >> 16) & 0o111
        assert f"pip install /autograder/source/{wheel.name}" in zf.read("setup.sh").decode()
        run = zf.read("run_autograder").decode()
        for script in ("setup.sh", "run_autograder"):
            syntax = subprocess.run(["bash", "-n"], input=zf.read(script), capture_output=True)
            assert syntax.returncode == 0, syntax.stderr
        assert "--format gradescope" in run and "/autograder" in run
    pypi = gradescope_bundle(tmp_path / "p.zip")
    with zipfile.ZipFile(pypi) as zf:
        assert "slamcourse==" in zf.read("setup.sh").decode()
        assert "course/chapters/01-basics.md" not in zf.namelist()


def test_run_autograder_grades_an_upload(tmp_path: Path) -> None:
    """The bundle's script, run as Gradescope would (in a stand-in /autograder folder)."""
    root = tmp_path / "autograder"
    bundle = gradescope_bundle(tmp_path / "b.zip", course=str(FIXTURE_COURSE))
    with zipfile.ZipFile(bundle) as zf:
        zf.extractall(root / "source")
    sub = make_submission(tmp_path / "s", 3, {"basics/count": right_answer(3, "basics/count")})
    (root / "submission").mkdir()
    with zipfile.ZipFile(root / "submission" / "upload.zip", "w") as zf:
        for f in sub.rglob("*"):
            zf.write(f, f.relative_to(sub).as_posix())
    env = {
        **os.environ,
        "AUTOGRADER_ROOT": str(root),
        "SLAMCOURSE_BIN": str(Path(sys.executable).parent / "slamcourse"),
    }
    done = subprocess.run(
        ["bash", str(root / "source" / "run_autograder")], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    results = json.loads((root / "results" / "results.json").read_text())
    assert results["score"] == 1, results
    assert len(results["tests"]) == 15


def test_prairielearn_entry_point(tmp_path: Path) -> None:
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "data.json").write_text(
        json.dumps({"params": {"slamcourse": {"course": str(FIXTURE_COURSE)}}})
    )
    make_submission(tmp_path / "student", 3, {"basics/count": right_answer(3, "basics/count")})
    results = grade_job(tmp_path, {})
    assert results["gradable"] is True
    assert results["score"] == round(1 / 15, 6)  # one of 15 exercises right, to 6 places
    (tmp_path / "student" / "submission.json").write_text("{")
    broken = grade_job(tmp_path, {})
    assert broken["gradable"] is False and "not valid JSON" in broken["format_errors"][0]
