"""Tests of the learner progress store (slamcourse.progress). Every test uses tmp_path."""

from __future__ import annotations

import importlib
import os
import shutil
import sqlite3
import stat
import subprocess
import sys
import tempfile
import traceback
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from hypothesis import settings
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, invariant, precondition, rule

from slamcourse.errors import EXIT_PROGRESS, ProgressError
from slamcourse.progress import (
    DB_FILENAME,
    SCHEMA_VERSION,
    VARIANT_MAX,
    Attempt,
    ExerciseState,
    Progress,
    default_db_path,
    default_home,
)
from slamcourse.verdict import Verdict

PASSED = Verdict("passed", 1.0, "Correct.")
FAILED = Verdict("failed", 0.0, "Not quite.", misconception="sign-flip")
PARTIAL = Verdict("failed", 0.5, "Half right.")
INVALID = Verdict("invalid", 0.0, "expected a number such as 0.25")
ERROR = Verdict("error", 0.0, "The grader failed.")
TIMEOUT = Verdict("timeout", 0.0, "Your code ran out of time.")

IS_ROOT = hasattr(os, "geteuid") and os.geteuid() == 0


@pytest.fixture
def db_path(tmp_path: Path) -> Path:
    return tmp_path / "home" / DB_FILENAME


@pytest.fixture
def progress(db_path: Path) -> Iterator[Progress]:
    with Progress.open(db_path) as store:
        yield store


def raw_user_version(path: Path) -> int:
    conn = sqlite3.connect(path)
    try:
        return int(conn.execute("PRAGMA user_version").fetchone()[0])
    finally:
        conn.close()


# ---------------------------------------------------------------------------------------------
# Creation and schema
# ---------------------------------------------------------------------------------------------


def test_fresh_db_is_created_with_version_1(db_path: Path) -> None:
    assert not db_path.parent.exists()
    with Progress.open(db_path) as store:
        assert store.path == db_path
    assert db_path.is_file()
    assert SCHEMA_VERSION == 1
    assert raw_user_version(db_path) == 1
    conn = sqlite3.connect(db_path)
    try:
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    finally:
        conn.close()
    assert {"meta", "exercise_state", "attempt", "reset_event"} <= tables


def test_reopen_keeps_data_and_does_not_remigrate(db_path: Path) -> None:
    with Progress.open(db_path) as store:
        store.record_attempt("ex", 5, "42", PASSED)
        seed = store.learner_seed
    with Progress.open(db_path) as store:
        assert store.learner_seed == seed
        assert store.state("ex").status == "solved"
        assert len(store.attempts("ex")) == 1
    assert raw_user_version(db_path) == SCHEMA_VERSION


def test_a_new_migration_step_upgrades_an_old_file(
    db_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import slamcourse.progress as mod

    with Progress.open(db_path) as store:
        store.record_attempt("ex", 1, "x", PASSED)
    v2 = ("ALTER TABLE attempt ADD COLUMN duration_s REAL",)
    monkeypatch.setattr(mod, "_MIGRATIONS", (*mod._MIGRATIONS, v2))
    monkeypatch.setattr(mod, "SCHEMA_VERSION", 2)
    with Progress.open(db_path) as store:
        assert store.state("ex").status == "solved"
    assert raw_user_version(db_path) == 2
    conn = sqlite3.connect(db_path)
    try:
        columns = {r[1] for r in conn.execute("PRAGMA table_info(attempt)")}
    finally:
        conn.close()
    assert "duration_s" in columns


def test_two_stores_on_one_file_see_each_other(db_path: Path) -> None:
    with Progress.open(db_path) as one, Progress.open(db_path) as two:
        assert one.learner_seed == two.learner_seed
        one.record_attempt("ex", 1, "x", FAILED)
        two.record_attempt("ex", 1, "y", FAILED)
        assert one.state("ex").attempts == 2
        two.reveal_hint("ex")
        assert one.reveal_hint("ex") == 2


def test_never_seen_exercise_is_pending_and_nothing_is_written(progress: Progress) -> None:
    assert progress.state("nope") == ExerciseState("nope", "pending", 0, 0, None, None)
    assert progress.states() == {}
    assert progress.attempts() == []


def test_closed_store_raises_progress_error(db_path: Path) -> None:
    store = Progress.open(db_path)
    store.close()
    store.close()  # idempotent
    with pytest.raises(ProgressError, match="closed"):
        store.state("ex")


# ---------------------------------------------------------------------------------------------
# Attempts
# ---------------------------------------------------------------------------------------------


def test_attempts_are_recorded_and_counted(progress: Progress) -> None:
    s1 = progress.record_attempt("ch/ex", 7, "1/2", FAILED)
    assert (s1.status, s1.attempts, s1.solved_at) == ("pending", 1, None)
    assert s1.updated_at is not None
    s2 = progress.record_attempt("ch/ex", 7, "abc", INVALID)
    assert s2.attempts == 1  # unreadable answers cost nothing
    s3 = progress.record_attempt("ch/ex", 7, "0.5", ERROR)
    assert s3.attempts == 1  # grader faults cost nothing
    s4 = progress.record_attempt("ch/ex", 7, "loop()", TIMEOUT)
    assert s4.attempts == 2
    s5 = progress.record_attempt("ch/ex", 7, "0.25", PARTIAL)
    assert s5.attempts == 3 and s5.status == "pending"
    assert progress.state("ch/ex") == s5

    log = progress.attempts("ch/ex")
    assert [a.answer for a in log] == ["1/2", "abc", "0.5", "loop()", "0.25"]
    assert [a.counted for a in log] == [True, False, False, True, True]
    first = log[0]
    assert isinstance(first, Attempt)
    assert first.exercise_id == "ch/ex"
    assert first.variant == 7
    assert first.status == "failed"
    assert first.score == 0.0
    assert first.misconception == "sign-flip"
    assert first.feedback == "Not quite."
    assert first.reset_at is None
    assert first.at.endswith("+00:00")  # UTC ISO time
    assert log[4].score == 0.5


def test_attempts_filter_and_limit(progress: Progress) -> None:
    for i in range(5):
        progress.record_attempt("a", 1, f"a{i}", FAILED)
        progress.record_attempt("b", 2, f"b{i}", FAILED)
    assert len(progress.attempts()) == 10
    assert [a.answer for a in progress.attempts("a", limit=2)] == ["a3", "a4"]  # newest, in order
    assert [a.answer for a in progress.attempts(limit=3)] == ["b3", "a4", "b4"]
    assert progress.attempts("b", limit=0) == []
    assert progress.attempts("c") == []


def test_solved_stays_solved(progress: Progress) -> None:
    progress.record_attempt("ex", 1, "1", FAILED)
    solved = progress.record_attempt("ex", 1, "2", PASSED)
    assert solved.status == "solved" and solved.solved
    assert solved.attempts == 2
    assert solved.solved_at is not None
    later = progress.record_attempt("ex", 1, "3", FAILED)
    assert later.status == "solved"
    assert later.solved_at == solved.solved_at
    again = progress.record_attempt("ex", 1, "2", PASSED)
    assert again.solved_at == solved.solved_at  # the first solve's time is kept
    assert again.attempts == 4
    assert progress.give_up("ex").status == "solved"


def test_special_text_is_stored_verbatim(progress: Progress) -> None:
    answer = "'; DROP TABLE attempt; --\n\tθ = π/4 ✓ \x00 end"
    progress.record_attempt("ex'\"", 0, answer, FAILED)
    assert progress.attempts("ex'\"")[0].answer == answer
    assert progress.attempts("ex'\"")[0].variant == 0


# ---------------------------------------------------------------------------------------------
# Hints, giving up, current exercise
# ---------------------------------------------------------------------------------------------


def test_hints(progress: Progress) -> None:
    assert progress.reveal_hint("ex") == 1
    assert progress.reveal_hint("ex") == 2
    assert progress.reveal_hint("other") == 1
    state = progress.state("ex")
    assert (state.hints_shown, state.attempts, state.status) == (2, 0, "pending")


def test_give_up(progress: Progress) -> None:
    progress.record_attempt("ex", 1, "1", FAILED)
    state = progress.give_up("ex")
    assert (state.status, state.attempts) == ("given_up", 1)
    assert progress.record_attempt("ex", 1, "2", FAILED).status == "given_up"
    solved = progress.record_attempt("ex", 1, "3", PASSED)
    assert solved.status == "solved"  # solving after giving up still counts as solved
    assert progress.give_up("fresh").status == "given_up"


def test_current_pointer(progress: Progress, db_path: Path) -> None:
    assert progress.current() is None
    progress.set_current("ch/ex2")
    assert progress.current() == "ch/ex2"
    progress.set_current("ch/ex3")
    assert progress.current() == "ch/ex3"
    with Progress.open(db_path) as other:
        assert other.current() == "ch/ex3"
    progress.set_current(None)
    assert progress.current() is None
    progress.set_current(None)  # unpinning twice is fine
    assert progress.current() is None


# ---------------------------------------------------------------------------------------------
# Reset
# ---------------------------------------------------------------------------------------------


def test_reset_one_exercise(progress: Progress) -> None:
    progress.record_attempt("a", 1, "x", PASSED)
    progress.reveal_hint("a")
    progress.record_attempt("b", 2, "y", FAILED)
    progress.set_current("a")
    seed = progress.variant_seed("a")

    progress.reset("a")
    assert progress.state("a") == ExerciseState.fresh("a")
    assert progress.state("b").attempts == 1
    assert set(progress.states()) == {"b"}
    assert progress.current() == "a"  # resetting one exercise keeps the pin
    assert progress.variant_seed("a") == seed
    # History is kept, marked as reset.
    (old,) = progress.attempts("a")
    assert old.answer == "x" and old.reset_at is not None
    assert progress.attempts("b")[0].reset_at is None
    # New attempts count from zero again.
    state = progress.record_attempt("a", 1, "z", FAILED)
    assert (state.status, state.attempts) == ("pending", 1)
    assert [a.reset_at is None for a in progress.attempts("a")] == [False, True]


def test_reset_all(progress: Progress) -> None:
    progress.record_attempt("a", 1, "x", PASSED)
    progress.record_attempt("b", 2, "y", FAILED)
    progress.give_up("c")
    progress.set_current("b")
    seed = progress.learner_seed

    progress.reset()
    assert progress.states() == {}
    assert progress.current() is None
    assert progress.state("a").status == "pending"
    assert progress.learner_seed == seed
    log = progress.attempts()
    assert len(log) == 2 and all(a.reset_at is not None for a in log)


def test_reset_of_untouched_exercise_is_harmless(progress: Progress) -> None:
    progress.reset("never")
    progress.reset()
    assert progress.states() == {}


# ---------------------------------------------------------------------------------------------
# Seeds
# ---------------------------------------------------------------------------------------------


def test_variant_seeds_stable_positive_and_distinct(tmp_path: Path) -> None:
    path_a = tmp_path / "a" / DB_FILENAME
    path_b = tmp_path / "b" / DB_FILENAME
    ids = [f"ch{c}/ex{i}" for c in range(3) for i in range(10)]
    with Progress.open(path_a) as store:
        seeds_a = {ex: store.variant_seed(ex) for ex in ids}
        assert store.variant_seed(ids[0]) == seeds_a[ids[0]]
        learner_a = store.learner_seed
    with Progress.open(path_a) as store:
        assert store.learner_seed == learner_a
        assert {ex: store.variant_seed(ex) for ex in ids} == seeds_a  # stable across reopen
    with Progress.open(path_b) as store:
        seeds_b = {ex: store.variant_seed(ex) for ex in ids}
        assert store.learner_seed != learner_a
    for seeds in (seeds_a, seeds_b):
        assert all(1 <= s <= VARIANT_MAX for s in seeds.values())
        assert len(set(seeds.values())) == len(ids)  # different exercises, different variants
    assert all(seeds_a[ex] != seeds_b[ex] for ex in ids)  # different learners


def test_variant_seed_is_stable_across_processes(db_path: Path) -> None:
    with Progress.open(db_path) as store:
        expected = store.variant_seed("ch/ex")
    code = (
        "import sys; from pathlib import Path; from slamcourse.progress import Progress\n"
        "with Progress.open(Path(sys.argv[1])) as p: print(p.variant_seed('ch/ex'))"
    )
    env = {**os.environ, "PYTHONHASHSEED": "12345"}
    out = subprocess.run(
        [sys.executable, "-c", code, str(db_path)],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    assert int(out.stdout) == expected


# ---------------------------------------------------------------------------------------------
# Broken files are reported, never replaced
# ---------------------------------------------------------------------------------------------


def assert_rejected_untouched(path: Path, match: str) -> ProgressError:
    before = path.read_bytes()
    mtime = path.stat().st_mtime_ns
    siblings = sorted(os.listdir(path.parent))
    with pytest.raises(ProgressError, match=match) as info:
        Progress.open(path)
    assert str(path) in str(info.value)
    assert path.read_bytes() == before
    assert path.stat().st_mtime_ns == mtime
    assert sorted(os.listdir(path.parent)) == siblings  # no journal or replacement left behind
    assert info.value.exit_code == EXIT_PROGRESS
    return info.value


def test_random_bytes_are_rejected_untouched(db_path: Path) -> None:
    db_path.parent.mkdir(parents=True)
    db_path.write_bytes(os.urandom(8192))
    err = assert_rejected_untouched(db_path, "is not a readable slamcourse progress database")
    assert "progress.sqlite3.bak" in str(err)
    assert "Move it aside" in str(err)


def test_text_file_is_rejected_untouched(db_path: Path) -> None:
    db_path.parent.mkdir(parents=True)
    db_path.write_text("my notes\n" * 100)
    assert_rejected_untouched(db_path, "not a readable slamcourse progress database")


def filled_db(path: Path) -> None:
    with Progress.open(path) as store:
        for i in range(200):
            store.record_attempt(f"ex{i % 5}", i, "answer " * 100, FAILED)


@pytest.mark.parametrize("fraction", [0.5, 0.9])
def test_truncated_db_is_rejected_untouched(db_path: Path, fraction: float) -> None:
    filled_db(db_path)
    data = db_path.read_bytes()
    assert len(data) > 16 * 4096
    db_path.write_bytes(data[: int(len(data) * fraction)])
    assert_rejected_untouched(db_path, "not a readable slamcourse progress database")


def test_truncated_header_is_rejected_untouched(db_path: Path) -> None:
    filled_db(db_path)
    db_path.write_bytes(db_path.read_bytes()[:60])
    assert_rejected_untouched(db_path, "not a readable slamcourse progress database")


def test_other_programs_sqlite_db_is_rejected_untouched(db_path: Path) -> None:
    db_path.parent.mkdir(parents=True)
    conn = sqlite3.connect(db_path)
    with conn:
        conn.execute("CREATE TABLE bookmarks (url TEXT)")
    conn.close()
    assert_rejected_untouched(db_path, "some other program")


def test_newer_schema_is_rejected_untouched(db_path: Path) -> None:
    Progress.open(db_path).close()
    conn = sqlite3.connect(db_path)
    conn.execute("PRAGMA user_version = 99")
    conn.close()
    err = assert_rejected_untouched(db_path, "newer slamcourse")
    assert "schema 99" in str(err)
    assert f"knows up to {SCHEMA_VERSION}" in str(err)
    assert "pip install -U slamcourse" in str(err)
    assert "SLAMCOURSE_HOME" in str(err)


def test_empty_file_is_initialised(db_path: Path) -> None:
    db_path.parent.mkdir(parents=True)
    db_path.touch()
    with Progress.open(db_path) as store:
        assert store.state("ex").status == "pending"
    assert raw_user_version(db_path) == SCHEMA_VERSION


def test_folder_in_place_of_the_file(db_path: Path) -> None:
    db_path.mkdir(parents=True)
    with pytest.raises(ProgressError, match="is a folder"):
        Progress.open(db_path)


# ---------------------------------------------------------------------------------------------
# Locations and permissions
# ---------------------------------------------------------------------------------------------


def test_slamcourse_home_is_respected(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    home = tmp_path / "learner-home"
    monkeypatch.setenv("SLAMCOURSE_HOME", str(home))
    assert default_home() == home
    assert default_db_path() == home / DB_FILENAME
    with Progress.open() as store:
        assert store.path == home / DB_FILENAME
        store.reveal_hint("ex")
    assert (home / DB_FILENAME).is_file()


def test_default_home_without_env_uses_platformdirs(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("SLAMCOURSE_HOME", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "xdg"))
    monkeypatch.setenv("HOME", str(tmp_path / "userhome"))
    home = default_home()
    assert home.name == "slamcourse"
    if sys.platform.startswith("linux"):
        assert home == tmp_path / "xdg" / "slamcourse"


def test_import_is_light() -> None:
    code = (
        "import sys, slamcourse.progress\n"
        "heavy = {'numpy', 'jinja2', 'platformdirs', 'yaml', 'scipy', 'hypothesis'}\n"
        "print(sorted(heavy & set(sys.modules)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


NOBODY = 65534
LAZY_IMPORTS = ("secrets",)  # what the progress store imports when it first needs it


def _without_privileges(body: Callable[[Path], None], tmp_path: Path) -> None:
    """Run ``body(folder)`` where file permissions apply: here, or, as root (whom they do not
    bind), in a forked child that has become ``nobody``, with a folder ``nobody`` owns; the
    child's failure is raised here with its traceback."""
    if not IS_ROOT:
        body(tmp_path)
        return
    for name in LAZY_IMPORTS:  # (nobody cannot read root's Python library to import them)
        importlib.import_module(name)
    folder = Path(tempfile.mkdtemp(prefix="slamcourse-nobody-"))  # (under /tmp: traversable)
    os.chown(folder, NOBODY, NOBODY)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never returns to pytest
        code = 0
        try:
            os.close(read)
            os.setgroups([])
            os.setgid(NOBODY)
            os.setuid(NOBODY)
            body(folder)
        except BaseException:
            os.write(write, traceback.format_exc().encode())
            code = 1
        os._exit(code)
    os.close(write)
    try:
        with os.fdopen(read, "rb") as report:
            failure = report.read().decode()
        _, status = os.waitpid(pid, 0)
        assert os.waitstatus_to_exitcode(status) == 0, failure
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _read_only_directory(base: Path) -> None:
    folder = base / "locked"
    folder.mkdir()
    folder.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        with pytest.raises(ProgressError, match="writable") as info:
            Progress.open(folder / DB_FILENAME)
        assert str(folder) in str(info.value)
        assert not (folder / DB_FILENAME).exists()
        with pytest.raises(ProgressError, match="progress folder"):
            Progress.open(folder / "sub" / DB_FILENAME)
    finally:
        folder.chmod(stat.S_IRWXU)


def test_read_only_directory_gives_progress_error(tmp_path: Path) -> None:
    _without_privileges(_read_only_directory, tmp_path)


def _read_only_file(base: Path) -> None:
    db_path = base / "home" / DB_FILENAME
    with Progress.open(db_path) as store:
        store.record_attempt("ex", 1, "x", PASSED)
    before = db_path.read_bytes()
    db_path.chmod(stat.S_IRUSR)
    try:
        with Progress.open(db_path) as store:
            assert store.state("ex").status == "solved"  # reading still works
            with pytest.raises(ProgressError, match="writable") as info:
                store.record_attempt("ex", 1, "y", FAILED)
            assert str(db_path) in str(info.value)
        assert db_path.read_bytes() == before
    finally:
        db_path.chmod(stat.S_IRUSR | stat.S_IWUSR)


def test_read_only_file_reads_but_refuses_writes(tmp_path: Path) -> None:
    _without_privileges(_read_only_file, tmp_path)


# ---------------------------------------------------------------------------------------------
# Property test: random operation sequences keep the invariants
# ---------------------------------------------------------------------------------------------

EXERCISES = st.sampled_from(["a", "b", "c"])
VERDICTS = st.sampled_from([PASSED, FAILED, PARTIAL, INVALID, ERROR, TIMEOUT])


class ProgressMachine(RuleBasedStateMachine):
    """Drives a real store and a tiny model side by side; they must always agree."""

    def __init__(self) -> None:
        super().__init__()
        self.folder = tempfile.mkdtemp(prefix="slamcourse-progress-")
        self.path = Path(self.folder) / DB_FILENAME
        self.store = Progress.open(self.path)
        # Model: exercise -> (status, attempts, hints); absent means pending with zeros.
        self.model: dict[str, tuple[str, int, int]] = {}
        self.solved_at: dict[str, str] = {}
        self.log_length = 0

    def teardown(self) -> None:
        self.store.close()
        shutil.rmtree(self.folder, ignore_errors=True)

    def _model(self, ex: str) -> tuple[str, int, int]:
        return self.model.get(ex, ("pending", 0, 0))

    @rule(ex=EXERCISES, verdict=VERDICTS, answer=st.text(max_size=20))
    def record(self, ex: str, verdict: Verdict, answer: str) -> None:
        status, attempts, hints = self._model(ex)
        before = self.store.state(ex)
        state = self.store.record_attempt(ex, self.store.variant_seed(ex), answer, verdict)
        self.log_length += 1
        attempts += int(verdict.counts_as_attempt)
        if verdict.passed:
            status = "solved"
        self.model[ex] = (status, attempts, hints)
        if before.status == "solved":
            assert state.status == "solved"
            assert state.solved_at == before.solved_at
        if state.solved_at is not None:
            self.solved_at.setdefault(ex, state.solved_at)

    @rule(ex=EXERCISES)
    def hint(self, ex: str) -> None:
        status, attempts, hints = self._model(ex)
        assert self.store.reveal_hint(ex) == hints + 1
        self.model[ex] = (status, attempts, hints + 1)

    @rule(ex=EXERCISES)
    def give_up(self, ex: str) -> None:
        status, attempts, hints = self._model(ex)
        new_status = "solved" if status == "solved" else "given_up"
        assert self.store.give_up(ex).status == new_status
        self.model[ex] = (new_status, attempts, hints)

    @rule(ex=EXERCISES)
    def reset_one(self, ex: str) -> None:
        self.store.reset(ex)
        self.model.pop(ex, None)
        self.solved_at.pop(ex, None)

    @rule()
    def reset_all(self) -> None:
        self.store.reset()
        self.model.clear()
        self.solved_at.clear()

    @precondition(lambda self: self.log_length > 0)
    @rule()
    def reopen(self) -> None:
        self.store.close()
        self.store = Progress.open(self.path)

    @invariant()
    def store_matches_model(self) -> None:
        states = self.store.states()
        for ex in ("a", "b", "c"):
            state = self.store.state(ex)
            assert state.attempts >= 0 and state.hints_shown >= 0
            assert (state.status, state.attempts, state.hints_shown) == self._model(ex)
            assert (state.solved_at is not None) == (ex in self.solved_at)
            if ex in self.solved_at:
                assert state.solved_at == self.solved_at[ex]
            if ex in self.model:
                assert states[ex] == state
        assert len(self.store.attempts()) == self.log_length  # the log only grows


ProgressMachine.TestCase.settings = settings(max_examples=25, stateful_step_count=25, deadline=None)
TestProgressMachine = ProgressMachine.TestCase
