"""Submissions: what `slamcourse submit` writes, and reading untrusted ones safely."""

from __future__ import annotations

import json
import os
import shutil
import stat
import zipfile
from pathlib import Path

import pytest

from slamcourse.batch.grade import GradeOptions, duplicate_learners, grade_all, grade_submission
from slamcourse.batch.submission import (
    MANIFEST,
    Limits,
    SubmissionError,
    course_hash,
    learner_id,
    read,
)
from slamcourse.cli import main
from slamcourse.progress import Progress
from tests.batch.conftest import CODE_ID, SOLUTION, make_submission, right_answer
from tests.conftest import FIXTURE_COURSE

COURSE = ["--course", str(FIXTURE_COURSE)]


def test_submit_hands_in_the_latest_answer_and_the_code_file(
    tmp_path: Path, private_home: Path
) -> None:
    main([*COURSE, "check", "basics/count", "--answer", "1"])
    with Progress.open(private_home / "progress.sqlite3") as store:
        seed = store.learner_seed
    main([*COURSE, "check", "basics/count", "--answer", right_answer(seed, "basics/count")])
    main([*COURSE, "check", "basics/distance", "--canonical", "--answer", "5"])  # practice
    workspace = private_home / "workspace" / "basics"
    workspace.mkdir(parents=True)
    (workspace / "range_bearing.py").write_text(SOLUTION)
    assert main([*COURSE, "submit", "--out", str(tmp_path / "sub.zip")]) == 0
    sub = read(tmp_path / "sub.zip")
    m = sub.manifest
    assert m.learner_id == learner_id(seed) and m.learner_seed == seed
    assert m.course_hash == course_hash(FIXTURE_COURSE)
    answers = {a.exercise: a for a in m.answers}
    assert set(answers) == {"basics/count", CODE_ID}  # the practice answer is not handed in
    assert answers["basics/count"].text == right_answer(seed, "basics/count")
    assert answers["basics/count"].attempts == 2
    assert sub.source(answers[CODE_ID]).decode() == SOLUTION
    assert main([*COURSE, "submit", "--out", str(tmp_path / "dir"), "--learner", "ada"]) == 0
    assert read(tmp_path / "dir").manifest.learner_id == "ada"
    result = grade_submission(tmp_path / "dir", GradeOptions(course=FIXTURE_COURSE, hidden_runs=0))
    assert result.status == "graded"
    assert {e.exercise: e.status for e in result.exercises}["basics/count"] == "passed"


def test_course_hash_changes_with_any_content(tmp_path: Path) -> None:
    copy = tmp_path / "c"
    shutil.copytree(FIXTURE_COURSE, copy)
    assert course_hash(copy) == course_hash(FIXTURE_COURSE)
    (copy / "exercises" / "basics" / "__pycache__").mkdir(exist_ok=True)
    (copy / "exercises" / "basics" / "__pycache__" / "x.pyc").write_bytes(b"x")
    (copy / "exercises" / ".hypothesis").mkdir()
    (copy / "exercises" / ".hypothesis" / "db").write_bytes(b"x")
    assert course_hash(copy) == course_hash(FIXTURE_COURSE)
    with open(copy / "chapters" / "01-basics.md", "a") as fh:
        fh.write(" ")
    assert course_hash(copy) != course_hash(FIXTURE_COURSE)


def zipped(path: Path, entries: dict[str, bytes], *, manifest: bool = True) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zf:
        if manifest:
            zf.writestr(MANIFEST, (FIXTURE_MANIFEST_DIR / MANIFEST).read_bytes())
        for name, data in entries.items():
            zf.writestr(name, data)
    return path


FIXTURE_MANIFEST_DIR = Path()


@pytest.fixture(autouse=True)
def manifest_dir(tmp_path_factory: pytest.TempPathFactory) -> None:
    global FIXTURE_MANIFEST_DIR
    FIXTURE_MANIFEST_DIR = make_submission(
        tmp_path_factory.mktemp("m") / "s", 5, {"basics/distance": "1"}
    )


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("/etc/passwd", "absolute path"),
        ("../escape.py", "outside the submission"),
        ("code/../../x.py", "outside the submission"),
        ("C:/x.py", "absolute path"),
        ("code\\x.py", "absolute path"),
    ],
)
def test_hostile_entry_names_are_refused(tmp_path: Path, name: str, words: str) -> None:
    path = zipped(tmp_path / "s.zip", {name: b"x"})
    with pytest.raises(SubmissionError, match=words):
        read(path)


def test_a_symlink_entry_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "s.zip"
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr(MANIFEST, (FIXTURE_MANIFEST_DIR / MANIFEST).read_bytes())
        info = zipfile.ZipInfo("code/link.py")
        info.external_attr = (stat.S_IFLNK | 0o777) << 16
        zf.writestr(info, "/etc/passwd")
    with pytest.raises(SubmissionError, match="symbolic link"):
        read(path)


def test_a_symlink_in_a_folder_is_refused(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {}, "x = 1\n")
    target = sub / "code" / "basics" / "range-bearing.py"
    target.unlink()
    os.symlink("/etc/passwd", target)
    with pytest.raises(SubmissionError, match="symbolic link"):
        read(sub)


def test_a_zip_bomb_stops_at_the_cap(tmp_path: Path) -> None:
    path = zipped(tmp_path / "bomb.zip", {"code/big.py": b"\0" * (3 * 1024 * 1024)})
    assert path.stat().st_size < 20_000
    with pytest.raises(SubmissionError, match="unpacks to more"):
        read(path)
    many = zipped(tmp_path / "many.zip", {f"code/f{i}.py": b"" for i in range(30)})
    with pytest.raises(SubmissionError, match="entries"):
        read(many, Limits(max_entries=10))
    total = zipped(tmp_path / "total.zip", {f"code/f{i}.py": b"1" * 1000 for i in range(10)})
    with pytest.raises(SubmissionError, match="unpacks to more"):
        read(total, Limits(max_total_bytes=5000))


def test_a_truncated_zip_is_refused(tmp_path: Path) -> None:
    whole = zipped(tmp_path / "whole.zip", {"code/x.py": os.urandom(5000)})
    cut = tmp_path / "cut.zip"
    cut.write_bytes(whole.read_bytes()[:3000])
    with pytest.raises(SubmissionError, match="not a readable zip"):
        read(cut)


def test_a_zipped_folder_is_accepted_without_the_archivers_extras(tmp_path: Path) -> None:
    path = tmp_path / "wrapped.zip"
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr("ada/" + MANIFEST, (FIXTURE_MANIFEST_DIR / MANIFEST).read_bytes())
        zf.writestr("__MACOSX/ada/._submission.json", b"\0")
        zf.writestr("ada/.DS_Store", b"\0")
        zf.writestr("ada/notes with spaces.txt", b"hi")
    sub = read(path)
    assert sub.manifest.learner_id == learner_id(5)
    assert set(sub.files) == {"notes with spaces.txt"}


def test_a_git_checkout_is_read_without_its_history(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {})
    (sub / ".git" / "objects").mkdir(parents=True)
    (sub / ".git" / "objects" / "x").write_bytes(b"\0" * 100)
    assert read(sub, Limits(max_entries=2)).files == {}


@pytest.mark.parametrize(
    ("change", "words"),
    [
        ({"format": 2}, "format 2"),
        ({"learner": {"id": "x", "name": None, "seed": "7"}}, "learner.seed"),
        ({"answers": [{"exercise": "basics/distance", "variant": 1}]}, "exactly one of"),
        ({"answers": "nope"}, "answers must be a list"),
        (
            {"answers": [{"exercise": "basics/x", "variant": 0, "file": "../x.py"}]},
            "outside",
        ),
        (
            {"answers": [{"exercise": "basics/x", "variant": 0, "file": "my code.py"}]},
            "not a plain file name",
        ),
        ({"learner": {"id": "a\nb", "name": "a\nb", "seed": 5}}, "printable"),
    ],
)
def test_malformed_manifests_say_which_field(
    tmp_path: Path, change: dict[str, object], words: str
) -> None:
    sub = make_submission(tmp_path / "s", 5, {}, manifest=change)
    with pytest.raises(SubmissionError, match=words):
        read(sub)


def test_not_json_and_no_manifest(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {})
    (sub / MANIFEST).write_bytes(b"\xff{")
    with pytest.raises(SubmissionError, match="not valid JSON"):
        read(sub)
    (sub / MANIFEST).unlink()
    with pytest.raises(SubmissionError, match=r"has no submission\.json"):
        read(sub)


# ------------------------------------------------------------------------------ claims


def grade_error(path: Path) -> str:
    result = grade_submission(path, GradeOptions(course=FIXTURE_COURSE))
    assert result.status == "error" and result.exercises == ()
    return result.error or ""


def test_a_tampered_variant_seed_is_rejected(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {"basics/distance": "1"})
    data = json.loads((sub / MANIFEST).read_text())
    data["answers"][0]["variant"] += 1
    (sub / MANIFEST).write_text(json.dumps(data))
    assert "claims variant" in grade_error(sub)


def test_a_learner_id_not_of_the_seed_is_rejected(tmp_path: Path) -> None:
    sub = make_submission(
        tmp_path / "s", 5, {}, manifest={"learner": {"id": learner_id(6), "name": None, "seed": 5}}
    )
    assert "does not belong to learner.seed" in grade_error(sub)


def test_another_course_version_is_rejected(tmp_path: Path) -> None:
    sub = make_submission(
        tmp_path / "s", 5, {}, manifest={"course": {"version": "9.9", "hash": "sha256:00"}}
    )
    assert "course version 9.9" in grade_error(sub)


def test_a_missing_code_file_is_an_answer_problem_not_a_crash(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {"basics/distance": "1"}, SOLUTION)
    (sub / "code" / "basics" / "range-bearing.py").unlink()
    result = grade_submission(sub, GradeOptions(course=FIXTURE_COURSE))
    code = {e.exercise: e for e in result.exercises}[CODE_ID]
    assert result.status == "graded" and code.status == "invalid"
    assert "is missing" in code.feedback


def test_unknown_exercises_are_a_warning(tmp_path: Path) -> None:
    sub = make_submission(
        tmp_path / "s",
        5,
        {},
        manifest={"answers": [{"exercise": "basics/nope", "variant": 0, "answer": "1"}]},
    )
    result = grade_submission(sub, GradeOptions(course=FIXTURE_COURSE))
    assert result.status == "graded"
    assert any("basics/nope" in w for w in result.warnings)


def test_a_code_file_that_is_not_utf8_is_unreadable(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {}, "x = 1\n")
    (sub / "code" / "basics" / "range-bearing.py").write_bytes(b"import math\n# caf\xe9\n")
    result = grade_submission(sub, GradeOptions(course=FIXTURE_COURSE))
    code = {e.exercise: e for e in result.exercises}[CODE_ID]
    assert code.status == "invalid"
    assert "code/basics/range-bearing.py:2: byte 0xe9 is not UTF-8" in code.feedback


def test_one_seed_under_two_names_is_flagged(tmp_path: Path) -> None:
    def named(who: str, seed: int) -> Path:
        return make_submission(
            tmp_path / who, seed, {}, manifest={"learner": {"id": who, "name": who, "seed": seed}}
        )

    paths = [named("ann", 8), named("ben", 8), named("cat", 9), named("cat2", 10)]
    grades = grade_all(paths, GradeOptions(course=FIXTURE_COURSE))
    warnings = duplicate_learners(grades)
    assert warnings == ["one learner seed is claimed by 2 learners: ann, ben"]
    again = grade_all(paths[2:3] * 2, GradeOptions(course=FIXTURE_COURSE))
    assert duplicate_learners(again) == ["learner cat appears in 2 submissions: cat, cat"]


def test_an_overlong_answer_is_not_parsed(tmp_path: Path) -> None:
    sub = make_submission(tmp_path / "s", 5, {"basics/distance": "1" * 20_000})
    result = grade_submission(sub, GradeOptions(course=FIXTURE_COURSE))
    distance = {e.exercise: e for e in result.exercises}["basics/distance"]
    assert distance.status == "invalid" and "longer than" in distance.feedback


def test_a_broken_reference_is_the_graders_error_not_the_learners(course_copy: Path) -> None:
    ref = course_copy / "exercises" / "basics" / "reference.py"
    ref.write_text(
        ref.read_text().replace("return math.hypot(dx, dy)", "raise RuntimeError('oops')", 1)
    )
    sub = make_submission(
        course_copy.parent / "s",
        5,
        {"basics/distance": "1"},
        manifest={"course": {"version": "custom", "hash": course_hash(course_copy)}},
    )
    result = grade_submission(sub, GradeOptions(course=course_copy))
    distance = {e.exercise: e for e in result.exercises}["basics/distance"]
    assert distance.status == "error", distance
    assert "grader's side" in distance.feedback
