"""Grading a small class: each verdict, hidden checks, determinism, one bad submission never
stops the batch, and the CLI's exit code says only whether grading ran."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import pytest

from slamcourse.batch.grade import (
    GradeOptions,
    SubmissionGrade,
    build_answers,
    grade_all,
    grade_submission,
    shard,
    without_timing,
)
from slamcourse.batch.submission import MANIFEST
from slamcourse.cli import main
from tests.batch.conftest import CODE_ID, COURSE, SOLUTION, make_submission, right_answer
from tests.conftest import FIXTURE_COURSE

WRONG_CODE = (
    "import math\ndef range_bearing(dx, dy, theta):\n"
    "    return dx*dx + dy*dy, math.atan2(dy, dx) - theta\n"
)
CRASH_CODE = "import os\ndef range_bearing(dx, dy, theta):\n    os._exit(3)\n"
# more than the 1 MiB one call may print (Limits.muted_after): a flood, on the first call
FLOOD_CODE = (
    "import math\ndef range_bearing(dx, dy, theta):\n"
    "    print('x' * 2_000_000)\n    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
)


@pytest.fixture(scope="module")
def graded(tmp_path_factory: pytest.TempPathFactory) -> tuple[list[Path], list[SubmissionGrade]]:
    """Five submissions graded once with two worker processes."""
    root = tmp_path_factory.mktemp("class")
    right = {ex: right_answer(11, ex) for ex in ("basics/distance", "basics/count")}
    paths = [
        make_submission(root / "a-right", 11, right, SOLUTION),
        make_submission(
            root / "b-wrong",
            12,
            {"basics/distance": "1e6", "basics/count": str(2 * _n(12))},
            WRONG_CODE,
        ),
        make_submission(root / "c-crash", 13, {"basics/distance": "abc"}, CRASH_CODE),
        make_submission(root / "d-flood", 14, {}, FLOOD_CODE),
        root / "e-missing.zip",
    ]
    return paths, grade_all(paths, GradeOptions(course=FIXTURE_COURSE), jobs=2)


def _n(learner_seed: int) -> int:
    from slamcourse.course.variants import variant
    from tests.batch.conftest import seed_of

    spec = COURSE.exercise("basics/count")
    return int(variant(spec, seed_of(learner_seed, "basics/count")).params["n"])


def by_id(grade: SubmissionGrade) -> dict[str, Any]:
    return {e.exercise: e for e in grade.exercises}


def test_results_come_in_the_order_given(graded: Any) -> None:
    paths, results = graded
    assert [r.submission for r in results] == [p.name for p in paths]


def test_a_right_submission_scores_its_answers(graded: Any) -> None:
    right = by_id(graded[1][0])
    assert right["basics/distance"].status == "passed"
    assert right["basics/count"].status == "passed"
    code = right[CODE_ID]
    assert code.status == "passed", code.feedback
    assert code.hidden == {"runs": 1, "failed": 0}
    assert "hidden check" in code.feedback
    assert right["basics/heading"].status == "missing"
    assert graded[1][0].score == 3.0
    assert graded[1][0].max_score == len(COURSE.exercise_ids)


def test_wrong_answers_fail_with_the_engines_feedback(graded: Any) -> None:
    wrong = by_id(graded[1][1])
    assert wrong["basics/distance"].status == "failed"
    assert wrong["basics/count"].misconception == "forgot-pose"
    assert wrong[CODE_ID].status == "failed"
    assert wrong[CODE_ID].misconception == "squared"
    assert wrong[CODE_ID].hidden == {"runs": 0, "failed": 0}
    assert wrong[CODE_ID].tests and wrong[CODE_ID].tests[0]["status"] == "failed"


def test_unreadable_answers_and_crashing_code_are_verdicts(graded: Any) -> None:
    crash = by_id(graded[1][2])
    assert crash["basics/distance"].status == "invalid"
    assert crash[CODE_ID].status == "failed"
    assert "stopped the grader's worker" in crash[CODE_ID].feedback


def test_flooding_output_stops_grading_at_once(graded: Any) -> None:
    flood = by_id(graded[1][3])
    assert flood[CODE_ID].status == "failed"
    assert (
        "printed more than 1 MiB of output in one call (test input 1 of" in flood[CODE_ID].feedback
    )
    assert flood[CODE_ID].seconds < 5  # not every call made: grading stops at the flood
    assert len(json.dumps(graded[1][3].to_dict())) < 50_000


def test_a_missing_file_is_that_submissions_error(graded: Any) -> None:
    missing = graded[1][4]
    assert missing.status == "error"
    assert "no such file" in (missing.error or "")


def test_grading_is_deterministic(graded: Any) -> None:
    paths, first = graded
    again = grade_all(paths[:1], GradeOptions(course=FIXTURE_COURSE), jobs=1)
    assert without_timing(again[0].to_dict()) == without_timing(first[0].to_dict())
    assert "seconds" in first[0].to_dict()


def memorised_source() -> str:
    """A 'solution' that knows the answers of exactly the inputs the local check uses."""
    from slamcourse.grading import testset

    # the inputs a local check uses: its visible test set (the examples, the boundary inputs of
    # the declared types, the course's shipped recording), with the reference's outputs
    local = testset.build(COURSE.exercise(CODE_ID)).visible
    assert any(c.origin.startswith("boundary") for c in local)
    table = {
        (float(c.kwargs["dx"]), float(c.kwargs["dy"]), float(c.kwargs["theta"])): tuple(
            float(v) for v in c.expected
        )
        for c in local
    }
    return (
        f"TABLE = {table!r}\n"
        "def range_bearing(dx, dy, theta):\n"
        "    return TABLE.get((float(dx), float(dy), float(theta)), (0.0, 0.0))\n"
    )


def test_hidden_checks_catch_code_fitted_to_the_local_inputs(tmp_path: Path) -> None:
    path = make_submission(tmp_path / "fitted", 21, {}, memorised_source())
    code = by_id(grade_submission(path, GradeOptions(course=FIXTURE_COURSE)))[CODE_ID]
    assert code.status == "failed"
    assert code.score == 0.0
    assert code.hidden == {"runs": 1, "failed": 1}
    assert "1 of 1 hidden check failed" in code.feedback
    assert "TABLE" not in code.feedback and "dx=" not in code.feedback  # no hidden input shown


@pytest.mark.slow
def test_a_hanging_function_times_out(tmp_path: Path) -> None:
    hang = "def range_bearing(dx, dy, theta):\n    while True:\n        pass\n"
    path = make_submission(tmp_path / "hang", 31, {}, hang)
    code = by_id(grade_submission(path, GradeOptions(course=FIXTURE_COURSE)))[CODE_ID]
    assert code.status == "timeout"


def test_shards_partition_the_sorted_paths() -> None:
    paths = [Path(f"s{i}") for i in (3, 1, 4, 0, 2)]
    parts = [shard(paths, f"{k}/2") for k in (1, 2)]
    assert parts == [[Path("s0"), Path("s2"), Path("s4")], [Path("s1"), Path("s3")]]
    with pytest.raises(Exception, match="K/N"):
        shard(paths, "3/2")


def test_cli_grades_writes_outside_nothing_and_exits_0(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    sub = make_submission(tmp_path / "in" / "x", 41, {"basics/distance": "1"})
    bad = tmp_path / "in" / "bad.zip"
    bad.write_bytes(b"PK\x03\x04 truncated")
    out = tmp_path / "out"
    before = sorted(p for p in tmp_path.rglob("*"))
    code = main(
        [
            "--course",
            str(FIXTURE_COURSE),
            "grade",
            str(sub),
            str(bad),
            "--jobs",  # (in two processes the system places: the flag reaches grade_all)
            "2",
            "--no-pin",
            "--format",
            "gradescope",
            "--out",
            str(out),
            "--csv",
            str(tmp_path / "g.csv"),
        ]
    )
    assert code == 0
    after = sorted(p for p in tmp_path.rglob("*"))
    new = [p for p in after if p not in before]
    assert all(p == tmp_path / "g.csv" or out in p.parents or p == out for p in new), new
    bad_result = json.loads((out / "bad" / "results.json").read_text())
    assert "not a readable zip" in bad_result["output"]
    rows = (tmp_path / "g.csv").read_text().splitlines()
    assert rows[2].startswith("learner-") and ",x," in rows[2]
    err = capsys.readouterr().err
    assert err.count("\n") == 3 and "no --secret" in err


def test_cli_refuses_to_run_without_submissions_or_a_course(tmp_path: Path) -> None:
    assert main(["--course", str(FIXTURE_COURSE), "grade"]) == 2
    sub = make_submission(tmp_path / "x", 51, {})
    assert main(["--course", str(tmp_path / "nowhere"), "grade", str(sub)]) == 2
    broken = tmp_path / "broken"
    (broken / "exercises").mkdir(parents=True)
    (broken / "chapters").mkdir()
    (broken / "chapters" / "01-x.md").write_text("---\nid: x\n---\n```{exercise} x/none\n```\n")
    assert main(["--course", str(broken), "grade", str(sub)]) >= 2


def test_the_bundled_course(tmp_path: Path) -> None:
    """The one test on the real course: a learner's submission made by `submit`, graded."""
    from slamcourse import __version__
    from slamcourse.batch.submission import build, write
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    settings = Settings.from_env(home=tmp_path / "home")
    with Engine.open(settings) as engine:
        first = next(e for e in engine.course.exercise_ids if not engine.is_code(e))
        engine.submit(first, "0")
        sub = build(engine, learner_name="ada")
    assert sub.manifest.course_version == __version__
    path = write(sub, tmp_path / "ada.zip")
    result = grade_submission(path, GradeOptions(hidden_runs=0))
    assert result.status == "graded", result.error
    graded = {e.exercise: e for e in result.exercises}
    assert graded[first].status in ("failed", "invalid", "passed")
    assert graded[first].variant == sub.manifest.answers[0].variant
    assert len(graded) == len(engine.course.exercise_ids)


def test_progress_bar_line() -> None:
    from slamcourse.batch.grade import bar_line

    assert bar_line(0, 4, width=8) == "[........] 0/4"
    assert bar_line(3, 4, width=8, label="s3.zip") == "[######..] 3/4 s3.zip"


def test_grade_refuses_without_isolation_unless_allowed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import slamcourse.engine

    monkeypatch.setattr(slamcourse.engine, "diagnostics", lambda s: {"isolation": "rlimits"})
    sub = make_submission(tmp_path / "x", 51, {"basics/distance": "1"})
    args = ["--course", str(FIXTURE_COURSE), "grade", str(sub), "--out", str(tmp_path / "o")]
    assert main(args) == 2
    assert not (tmp_path / "o").exists()
    assert main([*args, "--allow-no-isolation", "--csv", str(tmp_path / "a.csv")]) == 0
    assert (tmp_path / "o" / "x.json").is_file()
    merged = tmp_path / "all.csv"
    assert main(["grade", "--merge-csv", str(tmp_path / "a.csv"), "--csv", str(merged)]) == 0
    assert merged.read_text() == (tmp_path / "a.csv").read_text()
    assert main(["grade", "--merge-csv", str(tmp_path / "nope.csv"), "--csv", str(merged)]) == 2


def test_processes_take_the_largest_submissions_first(tmp_path: Path) -> None:
    """Longest-processing-time first: a batch does not end on one long submission while the
    other processes idle. Most code files first, then the most bytes; ties keep the given order
    (results are still reported in the order given)."""
    import zipfile

    from slamcourse.batch.grade import _largest_first

    def archive(name: str, files: dict[str, int]) -> Path:
        path = tmp_path / name
        with zipfile.ZipFile(path, "w") as z:
            for inner, size in files.items():
                z.writestr(inner, "x" * size)
        return path

    folder = tmp_path / "folder"
    (folder / "code").mkdir(parents=True)
    for k in range(3):
        (folder / "code" / f"e{k}.py").write_text("pass\n")
    paths = [
        archive("text-only.zip", {"submission.json": 5000}),
        archive("two-code.zip", {"submission.json": 10, "code/a.py": 10, "code/b.py": 10}),
        archive("one-code.zip", {"submission.json": 10, "code/a.py": 9000}),
        folder,
        tmp_path / "missing.zip",
        archive("two-code-big.zip", {"submission.json": 10, "code/a.py": 900, "code/b.py": 10}),
    ]
    assert _largest_first(paths) == [3, 5, 1, 2, 0, 4]


def _blas_threads() -> set[int]:
    from threadpoolctl import threadpool_info

    return {i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"}


def test_a_batch_computes_with_one_blas_thread_and_gives_them_back(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every grading process computes with one BLAS thread (N processes for N cores; results
    independent of --jobs); a batch graded in this process gives its threads back."""
    import os
    import subprocess
    import sys

    import numpy  # noqa: F401 (its BLAS loaded)

    from slamcourse.batch import grade

    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    before = _blas_threads()
    seen: list[tuple[set[int], str | None]] = []

    def probe(path: Path, *args: Any, **kwargs: Any) -> SubmissionGrade:
        seen.append((_blas_threads(), os.environ.get("OPENBLAS_NUM_THREADS")))
        return SubmissionGrade(path.name, None, "error", error="probe")

    monkeypatch.setattr(grade, "grade_submission", probe)
    grade_all([tmp_path / "a.zip", tmp_path / "b.zip"], GradeOptions(course=FIXTURE_COURSE))
    assert seen == [({1}, "1"), ({1}, "1")]  # (and a BLAS library loaded meanwhile: one)
    assert _blas_threads() == before
    assert "OPENBLAS_NUM_THREADS" not in os.environ
    # what each process of --jobs N runs first, for good (also for scipy, loaded after it)
    probe_process = (
        "import numpy, os\n"
        "from threadpoolctl import threadpool_info\n"
        "from slamcourse.batch.grade import _grading_process\n"
        "_grading_process()\n"
        "import gc; gc.collect()\n"
        "import scipy.linalg\n"
        "print(sorted({i['num_threads'] for i in threadpool_info() if i['user_api'] == 'blas'}),"
        " len(threadpool_info()), os.environ['OPENBLAS_NUM_THREADS'])\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    done = subprocess.run(
        [sys.executable, "-c", probe_process], env=env, capture_output=True, text=True
    )
    assert done.stdout.split() == ["[1]", "2", "1"], done.stderr


def test_a_shared_answer_is_built_with_its_misconceptions_values() -> None:
    """What grading an answer may compute is computed once for a whole batch, in one process:
    the reference's value and, where the kind computes them from the variant's parameters, its
    misconceptions' (a grading process that adopts them computes neither for a wrong answer).
    An expression's reference and misconceptions are evaluated at the formula's sampled points
    (arrays, which are never kept): nothing to share."""
    kept = build_answers(FIXTURE_COURSE, "basics/count")  # n = 3 (the canonical variant)
    assert sorted((name, value) for (_file, name, _args), value in kept.items()) == [
        ("count", 9),
        ("count_forgot_pose", 6),
    ]
    kept = build_answers(FIXTURE_COURSE, "basics/offset")
    assert [name for _file, name, _args in kept] == ["offset", "offset_swapped"]
    assert build_answers(FIXTURE_COURSE, "basics/slope") == {}


def test_grading_processes_are_pinned_one_per_cpu_when_there_are_enough(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """``--jobs N`` pins its N processes to N CPUs of their own when this process may run on
    at least N; with fewer, or one job (graded in-process), the system places them."""
    from slamcourse.batch import grade

    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {3, 1, 7, 5})
    assert grade.cpus_to_pin(2) == [1, 3]
    assert grade.cpus_to_pin(4) == [1, 3, 5, 7]
    assert grade.cpus_to_pin(5) == []
    assert grade.cpus_to_pin(1) == []


def _pinned(cpus: list[int], taken: Any, found: Any) -> None:
    from slamcourse.batch.grade import _grading_process

    _grading_process(cpus, taken)
    found.put(sorted(os.sched_getaffinity(0)))


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="needs two CPUs")
def test_each_grading_process_runs_on_its_own_cpu() -> None:
    """As ``grade_all`` starts its pool's processes: each takes the next CPU for itself (and
    for its sandboxes, which inherit it)."""
    import multiprocessing

    from slamcourse.batch.grade import cpus_to_pin

    cpus = cpus_to_pin(2)
    context = multiprocessing.get_context("forkserver")
    taken, found = context.Value("i", 0), context.Queue()
    for _ in range(2):
        process = context.Process(target=_pinned, args=(cpus, taken, found))
        process.start()
        process.join(60)
    assert sorted(found.get(timeout=5) for _ in range(2)) == [[cpus[0]], [cpus[1]]]


def test_the_long_parts_of_the_submissions_graded_last_go_first(tmp_path: Path) -> None:
    """A batch does not end on one learner's slow optimiser: the submissions graded last (a
    tenth, at least four per process) are graded in parts, and the parts with the exercises
    that may run long go before everything else, the rest last in pieces; every exercise of a
    split submission is in exactly one of its parts. One process, or nothing that runs long:
    whole submissions, largest first."""
    from slamcourse.batch.grade import _largest_first, plan

    paths = []
    for k in range(12):
        (tmp_path / f"s{k}").mkdir()
        (tmp_path / f"s{k}" / "a.py").write_text("x" * (100 * k + 1))
        paths.append(tmp_path / f"s{k}")
    order = _largest_first(paths)
    long = frozenset({"b/long", "c/long"})
    tasks = plan(paths, long, 2)
    last = order[4:]  # (eight: four per process)
    assert [i for i, _ in tasks] == last + order[:4] + last
    assert all(part is not None and part.inside for _, part in tasks[:8])
    assert all(part is None for _, part in tasks[8:12])
    assert all(part is not None and not part.inside for _, part in tasks[12:])
    first, rest = tasks[0][1], tasks[-1][1]
    assert first is not None and rest is not None
    for ex in ("a/short", "b/long", "c/long", "d/text"):
        assert (ex in first) != (ex in rest)
    assert plan(paths, long, 1) == plan(paths, frozenset(), 2) == [(i, None) for i in order]
    big = [tmp_path / f"missing-{k}.zip" for k in range(200)]
    assert sum(part is not None and part.inside for _, part in plan(big, long, 2)) == 20
    # the rest in pieces: the other code exercises dealt out in turn, the last piece every
    # exercise not in another part; each piece of all split submissions, then the next
    others = ["a/short", "b/long", "c/long", "e/code", "f/code", "g/code"]
    tasks = plan(paths, long, 2, others)
    assert [i for i, _ in tasks] == last + order[:4] + last * 3
    pieces = [tasks[k][1] for k in (0, 12, 20, 28)]
    assert tasks[12:20] == [(i, pieces[1]) for i in last]
    assert [p.exercises if p and p.inside else None for p in pieces[1:3]] == [
        frozenset({"a/short", "g/code"}),
        frozenset({"e/code"}),
    ]
    for ex in ("a/short", "b/long", "c/long", "d/text", "e/code", "f/code", "g/code"):
        assert sum(ex in p for p in pieces if p is not None) == 1, ex


def test_a_submission_graded_in_parts_gets_the_grade_it_gets_whole(
    graded: Any, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """Split (the code exercise taken for one that may run long), every submission of the
    class, right, wrong, crashing, flooding, missing or with warnings, is graded exactly as it
    is whole: its exercises in the course's order, its warnings once, its error its own."""
    from slamcourse.batch import grade

    paths, whole = graded
    warned = make_submission(
        tmp_path / "warned", 31, {"basics/distance": "1"}, SOLUTION, manifest={"engine": "0.0.1"}
    )
    manifest = json.loads((warned / MANIFEST).read_text())
    manifest["answers"].append({"exercise": "nope/not-here", "variant": 0, "answer": "2"})
    (warned / MANIFEST).write_text(json.dumps(manifest))
    alone = grade_all([warned], GradeOptions(course=FIXTURE_COURSE), jobs=1)
    assert len(alone[0].warnings) == 2 and len(alone[0].exercises) == len(whole[0].exercises)
    monkeypatch.setattr(grade, "_long_exercises", lambda course: frozenset({CODE_ID}))
    assert grade.plan(paths, frozenset({CODE_ID}), 2)[0][1] is not None
    split = grade_all([*paths, warned], GradeOptions(course=FIXTURE_COURSE), jobs=2, pin=False)
    assert [without_timing(g.to_dict()) for g in split] == [
        without_timing(g.to_dict()) for g in [*whole, *alone]
    ]


def test_a_task_asked_to_stop_leaves_the_rest_of_its_answers_to_other_tasks(
    graded: Any,
) -> None:
    """Asked to stop, a task finishes its current answer and grades no other: it lists the
    exercises it graded (and those not handed in), says which it left, and the tasks that
    grade what it left give, merged, the grade the submission gets whole."""
    from slamcourse.batch.grade import Part, _grade, merged

    paths, whole = graded
    options = GradeOptions(course=FIXTURE_COURSE)
    first, left = _grade(paths[0], options, stop=lambda: True)
    assert left == {"basics/count", CODE_ID}  # (text first: basics/distance was graded)
    assert "basics/distance" in by_id(first) and not left & set(by_id(first))
    assert by_id(first)["basics/offset"].status == "missing"
    rest, none = _grade(paths[0], options, part=Part(left, inside=True))
    assert none == frozenset() and set(by_id(rest)) == left
    together = merged([first, rest], COURSE.exercise_ids)
    assert without_timing(together.to_dict()) == without_timing(whole[0].to_dict())
    assert _grade(paths[0], options, stop=lambda: False)[1] == frozenset()


def test_a_process_with_nothing_to_do_stops_the_tasks_begun_first() -> None:
    from slamcourse.batch.grade import STEAL_AFTER, _to_stop

    now = 100.0
    out = [(0, now - 5), (1, 0.0), (2, now - 9), (3, now - STEAL_AFTER / 2)]
    assert _to_stop(out, 1, now) == [2]
    assert _to_stop(out, 2, now) == [2, 0]
    assert _to_stop(out, 3, now) == [2, 0]  # (not one just begun, nor one not yet begun)
    assert _to_stop(out, 0, now) == []


def test_what_a_stopped_task_left_is_dealt_out_long_exercises_first() -> None:
    from slamcourse.batch.grade import Part, _shares

    code = ["a/code", "b/long", "c/code", "d/code"]
    left = frozenset({"a/code", "b/long", "d/code", "t/text"})
    shares = _shares(left, code, frozenset({"b/long"}), 2)
    assert shares == [
        Part(frozenset({"b/long", "d/code", "t/text"}), inside=True),
        Part(frozenset({"a/code"}), inside=True),
    ]
    assert _shares(frozenset({"t/text"}), code, frozenset(), 2) == [
        Part(frozenset({"t/text"}), inside=True)
    ]
    assert shares[1].single and not shares[0].single  # (a piece of one is never asked)
    assert not Part(frozenset({"a/code"}), inside=False).single
    for count in (1, 2, 3, 7):  # every exercise left in exactly one piece, no piece empty
        pieces = _shares(left, code, frozenset({"b/long"}), count)
        assert len(pieces) == min(count, 3) and all(p.exercises for p in pieces)
        assert sorted(ex for p in pieces for ex in p.exercises) == sorted(left)


def test_a_class_whose_every_task_is_stopped_gets_the_grades_it_gets_whole(
    graded: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    """More processes than submissions, and every task out asked to stop at once (begun or
    not): each submission is graded one answer per task, and every grade is still the one it
    gets whole."""
    from slamcourse.batch import grade

    paths, whole = graded
    cut: list[int] = []
    shares = grade._shares

    def spy(*args: Any) -> list[Any]:
        cut.append(len(shares(*args)))
        return shares(*args)

    monkeypatch.setattr(grade, "_to_stop", lambda out, idle, now: [slot for slot, _ in out])
    monkeypatch.setattr(grade, "_shares", spy)
    split = grade_all(paths, GradeOptions(course=FIXTURE_COURSE), jobs=6, pin=False)
    assert len(cut) >= 3  # (a, b: three answers each, c: two; d: one; e: none, in error)
    assert [without_timing(g.to_dict()) for g in split] == [
        without_timing(g.to_dict()) for g in whole
    ]


def test_merging_parts_keeps_the_courses_order_and_any_parts_error() -> None:
    from slamcourse.batch.grade import ExerciseGrade, merged

    def ex(name: str) -> ExerciseGrade:
        return ExerciseGrade(name, name, "code", 1, 0, "passed", 1.0, "ok", seconds=0.5)

    a = SubmissionGrade("s", "l", "graded", (ex("c"), ex("a")), None, ("w1", "w2"), 1.0, "f")
    b = SubmissionGrade("s", "l", "graded", (ex("b"),), None, ("w2",), 2.0, "f")
    whole = merged([a, b], ["a", "b", "c"])
    assert [e.exercise for e in whole.exercises] == ["a", "b", "c"]
    assert whole.warnings == ("w1", "w2") and whole.seconds == 3.0 and whole.score == 3.0
    assert whole.fingerprint == "f" and whole.status == "graded"
    died = SubmissionGrade("s", None, "error", error="the grading process failed: boom")
    for parts in ([a, died], [died, b]):
        failed = merged(parts, ["a", "b", "c"])
        assert failed.status == "error" and failed.error == died.error
        assert failed.exercises == ()
    assert merged([a], ["a", "c"]) is a


def test_a_submission_grades_text_then_code_without_scipy_then_code_with_it(
    tmp_path: Path,
) -> None:
    """The order a submission's answers are graded in (results keep the course's): text while
    the zygotes start, then the code whose workers come from the zygote without scipy, then
    the code that names it: one switch between the two zygotes; within each, the exercises
    that may run long first."""
    from slamcourse.batch.grade import _grading_order, _source
    from slamcourse.batch.submission import read

    plain = read(make_submission(tmp_path / "plain", 41, {"basics/distance": "1"}, SOLUTION))
    uses = read(make_submission(tmp_path / "uses", 42, {}, "import scipy\n" + SOLUTION))
    assert [_grading_order(a, _source(plain, a))[0] for a in plain.manifest.answers] == [0, 1]
    assert [_grading_order(a, _source(uses, a))[0] for a in uses.manifest.answers] == [2]
    text, code = plain.manifest.answers
    long = frozenset({CODE_ID})  # (taken for one that may run long: it goes first of its kind)
    assert _grading_order(code, SOLUTION, long) == (1, False) < _grading_order(code, SOLUTION)
    assert _grading_order(text, None, long) == (0, True)


def test_a_graded_submission_leaves_nothing_cached_in_its_deleted_home(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Each submission is graded in a temporary home, deleted after its engine closes; the
    process's cache then goes back to what it was, so nothing parsed later (another engine's
    exercise, a figure) is written into the deleted home, which would bring it back."""
    import tempfile

    from slamcourse.settings import cache_dir

    before = cache_dir()
    homes = tmp_path / "homes"
    homes.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(homes))
    sub = make_submission(tmp_path / "s", 41, {"basics/distance": "1"}, SOLUTION)
    [graded] = grade_all([sub], GradeOptions(course=FIXTURE_COURSE), jobs=1)
    assert graded.status == "graded"
    assert cache_dir() == before
    assert list(homes.iterdir()) == []
