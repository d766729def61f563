"""Every exercise can be passed alone, as a learner would: a fresh process and a fresh home.

An earlier exercise in the same process must never be what makes a later one work. Here
nothing is shared: each check runs ``python -m slamcourse`` in a new interpreter with an empty
``SLAMCOURSE_HOME`` (so no recorded inputs are replayed and no parse cache is used).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from tests.conftest import REPO

COURSE_ROOT = bundled_course_root()


def _run(args: list[str], home: Path, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    env = {
        **os.environ,
        "PYTHONPATH": str(REPO / "src"),
        "SLAMCOURSE_HOME": str(home),
        "NO_COLOR": "1",
    }
    env.pop("SLAMCOURSE_COURSE", None)
    return subprocess.run(
        [sys.executable, *args],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        cwd=home,
    )


def _code_exercises() -> list[tuple[str, Path]]:
    course = load_course(COURSE_ROOT)
    found = []
    for ex_id in course.exercise_ids:
        spec = course.exercise(ex_id)
        if spec.kind == "code":
            found.append((ex_id, spec.options.solution))
    return found


def test_encoding_a_list_argument_needs_no_numpy(tmp_path: Path) -> None:
    """The protocol encodes containers by type, whether or not numpy has been imported."""
    code = (
        "import json, sys\n"
        "from slamcourse.sandbox.protocol import encode_arg\n"
        "assert 'numpy' not in sys.modules, 'numpy was imported by the protocol'\n"
        "print(json.dumps(encode_arg([[0.5, (1, 2)], {'k': [True]}])))\n"
    )
    done = _run(["-c", code], tmp_path)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout) == [[0.5, {"$tuple": [1, 2]}], {"$dict": [["k", [True]]]}]


def test_chapter_8_alone_validates(tmp_path: Path) -> None:
    """Validating only the occupancy chapter (whose code exercise takes lists) finds nothing.

    Before the protocol fix, ``ray-update``'s solution failed here with "cannot send a list to
    the sandbox", hidden in a full-course run because an earlier chapter imported numpy."""
    course = tmp_path / "course"
    (course / "chapters").mkdir(parents=True)
    shutil.copy(COURSE_ROOT / "chapters" / "08-occupancy.md", course / "chapters")
    shutil.copytree(COURSE_ROOT / "exercises" / "occupancy", course / "exercises" / "occupancy")
    home = tmp_path / "home"
    home.mkdir()
    # --record (re)writes the copy's recordings first: whether the real course's shipped ones
    # are current is not this test's question (validating the real course asks it)
    args = ["validate", str(course), "--variants", "2", "--record", "--json"]
    done = _run(["-m", "slamcourse", *args], home)
    assert done.returncode == 0, done.stdout + done.stderr
    report = json.loads(done.stdout)
    assert report["problems"] == []
    assert report["exercises"] == len(list((course / "exercises" / "occupancy").glob("*.yaml")))


@pytest.mark.slow
def test_every_code_solution_passes_alone(tmp_path: Path) -> None:
    """``slamcourse check ID --file <its solution>``: one fresh process and home per exercise."""
    exercises = _code_exercises()
    assert len(exercises) >= 17

    def check(item: tuple[str, Path]) -> tuple[str, int, str]:
        ex_id, solution = item
        home = tmp_path / ex_id.replace("/", "--")
        home.mkdir()
        done = _run(["-m", "slamcourse", "check", ex_id, "--file", str(solution)], home)
        return ex_id, done.returncode, done.stdout + done.stderr

    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(check, exercises))
    failures = [f"{ex_id} (exit {rc}):\n{out}" for ex_id, rc, out in results if rc != 0]
    assert not failures, "\n\n".join(failures)


_CHAPTER_ALONE = """
import json, sys
from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.course.variants import variant
from slamcourse.errors import CourseError
from slamcourse.kinds import get_kind

course = load_course(bundled_course_root())
problems, checked = [], 0
for ex_id in course.chapter(sys.argv[1]).exercises:
    spec = course.exercise(ex_id)
    if spec.kind == "code":  # graded by test_every_code_solution_passes_alone
        continue
    checked += 1
    try:
        problems += [str(p) for p in get_kind(spec.kind).self_test(spec, variant(spec, 0))]
    except CourseError as exc:
        problems += [str(p) for p in exc.problems]
print(json.dumps({"checked": checked, "problems": problems}))
"""


@pytest.mark.slow
def test_every_chapter_alone_accepts_its_reference_answers(tmp_path: Path) -> None:
    """Each chapter in its own interpreter: the canonical variant of every answer exercise
    computes, its reference answer passes and its misconceptions are recognised, with only
    that chapter's reference.py imported."""
    chapters = [ch.id for ch in load_course(COURSE_ROOT).chapters]
    assert len(chapters) >= 8

    def check(chapter: str) -> tuple[str, int, str]:
        home = tmp_path / chapter
        home.mkdir()
        done = _run(["-c", _CHAPTER_ALONE, chapter], home)
        return chapter, done.returncode, done.stdout + done.stderr

    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(check, chapters))
    checked = 0
    for chapter, rc, out in results:
        assert rc == 0, f"{chapter}:\n{out}"
        report = json.loads(out)
        assert report["problems"] == [], chapter
        checked += report["checked"]
    assert checked >= 30
