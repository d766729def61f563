"""Learner progress, kept in an embedded SQLite file (``<home>/progress.sqlite3``).

What is stored:

- ``meta``: key/value pairs: the learner's random seed (``learner_seed``, created at first open)
  and the exercise pinned by ``slamcourse goto`` (``current``, absent when none is pinned).
- ``exercise_state``: one row per exercise the learner has touched: status (``pending``,
  ``solved``, ``given_up``), counted attempts, hints shown, first-solve time, last update.
- ``attempt``: an append-only log of every answer checked, with its verdict.
- ``reset_event``: one row per ``reset``.

Resets and history: a reset deletes the ``exercise_state`` rows it covers (so the exercise is
pending again, with zero attempts and hints) but never deletes attempts. Instead it records a
``reset_event`` and stamps every attempt it covers with that event's id, so ``attempts()`` still
shows the whole history and each :class:`Attempt` says whether (and when) it was reset
(:attr:`Attempt.reset_at`). Nothing a learner typed is ever thrown away by slamcourse itself.

Reading states costs no query: the store keeps an in-memory copy of ``exercise_state``, updated
entry by entry by its own writes (after they commit) and read again whole when another
connection committed (``PRAGMA data_version``), e.g. the terminal while the browser face runs.
:meth:`Progress.changes_since` tells a reader which exercises changed since it last looked, so
the engine's summary is kept up to date instead of recomputed on every answer.

Robustness: the schema is versioned with ``PRAGMA user_version`` and upgraded by the ordered
steps in ``_MIGRATIONS``; every write runs in one ``BEGIN IMMEDIATE`` transaction; a file that is
not a readable progress database, or was written by a newer slamcourse, is reported as a
:class:`~slamcourse.errors.ProgressError` naming the file and the fix. The file is never replaced.

This module is imported by every CLI call, so it imports only the standard library at top level.
"""

from __future__ import annotations

import sqlite3
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from types import TracebackType
from typing import Literal, cast

from slamcourse.errors import ProgressError
from slamcourse.settings import default_home
from slamcourse.verdict import Status, Verdict

__all__ = [
    "DB_FILENAME",
    "SCHEMA_VERSION",
    "Attempt",
    "ExerciseState",
    "ExerciseStatus",
    "Progress",
    "default_db_path",
    "default_home",
]

DB_FILENAME = "progress.sqlite3"
BUSY_TIMEOUT_S = 5.0
VARIANT_MAX = 2**31 - 1
"""Variant seeds are in ``[1, VARIANT_MAX]``; 0 is reserved for the canonical variant."""

ExerciseStatus = Literal["pending", "solved", "given_up"]


# --------------------------------------------------------------------------------------------
# All SQL lives here: the schema migrations and every query. Values are always bound parameters;
# the only formatted statement is ``PRAGMA user_version``, whose value is an int from this module
# (SQLite cannot bind PRAGMA arguments).
# --------------------------------------------------------------------------------------------

_MIGRATIONS: tuple[tuple[str, ...], ...] = (
    # v1: the initial schema. To add v2, append one more tuple of statements; never edit v1.
    (
        """CREATE TABLE meta (
            key   TEXT PRIMARY KEY,
            value TEXT NOT NULL
        )""",
        """CREATE TABLE exercise_state (
            exercise_id TEXT PRIMARY KEY,
            status      TEXT NOT NULL DEFAULT 'pending'
                        CHECK (status IN ('pending', 'solved', 'given_up')),
            attempts    INTEGER NOT NULL DEFAULT 0 CHECK (attempts >= 0),
            hints_shown INTEGER NOT NULL DEFAULT 0 CHECK (hints_shown >= 0),
            solved_at   TEXT,
            updated_at  TEXT NOT NULL
        )""",
        """CREATE TABLE reset_event (
            id          INTEGER PRIMARY KEY,
            at          TEXT NOT NULL,
            exercise_id TEXT  -- NULL: every exercise was reset
        )""",
        """CREATE TABLE attempt (
            id            INTEGER PRIMARY KEY,
            at            TEXT NOT NULL,
            exercise_id   TEXT NOT NULL,
            variant       INTEGER NOT NULL,
            answer        TEXT NOT NULL,
            status        TEXT NOT NULL
                          CHECK (status IN ('passed', 'failed', 'invalid', 'timeout', 'error')),
            score         REAL NOT NULL CHECK (score >= 0.0 AND score <= 1.0),
            misconception TEXT,
            feedback      TEXT NOT NULL,
            counted       INTEGER NOT NULL CHECK (counted IN (0, 1)),
            reset_id      INTEGER REFERENCES reset_event (id)
        )""",
        "CREATE INDEX attempt_by_exercise ON attempt (exercise_id, id)",
    ),
)
SCHEMA_VERSION = len(_MIGRATIONS)


class _SQL:
    """Every query the store runs (namespace only)."""

    user_version = "PRAGMA user_version"
    set_user_version = "PRAGMA user_version = {:d}"
    quick_check = "PRAGMA quick_check"
    foreign_keys_on = "PRAGMA foreign_keys = ON"
    begin = "BEGIN IMMEDIATE"
    count_schema_objects = "SELECT count(*) FROM sqlite_master"
    data_version = "PRAGMA data_version"

    get_meta = "SELECT value FROM meta WHERE key = ?"
    set_meta = (
        "INSERT INTO meta (key, value) VALUES (?, ?) "
        "ON CONFLICT (key) DO UPDATE SET value = excluded.value"
    )
    add_meta = "INSERT OR IGNORE INTO meta (key, value) VALUES (?, ?)"
    del_meta = "DELETE FROM meta WHERE key = ?"

    _state_cols = "exercise_id, status, attempts, hints_shown, solved_at, updated_at"
    get_state = f"SELECT {_state_cols} FROM exercise_state WHERE exercise_id = ?"
    all_states = f"SELECT {_state_cols} FROM exercise_state ORDER BY exercise_id"
    ensure_state = (
        "INSERT INTO exercise_state (exercise_id, updated_at) VALUES (?, ?) "
        "ON CONFLICT (exercise_id) DO NOTHING"
    )
    # Parameters: ?1 counted (0/1), ?2 passed (0/1), ?3 now, ?4 exercise_id.
    apply_attempt = """UPDATE exercise_state SET
            attempts   = attempts + ?1,
            status     = CASE WHEN ?2 THEN 'solved' ELSE status END,
            solved_at  = CASE WHEN ?2 AND solved_at IS NULL THEN ?3 ELSE solved_at END,
            updated_at = ?3
        WHERE exercise_id = ?4"""
    add_hint = (
        "UPDATE exercise_state SET hints_shown = hints_shown + 1, updated_at = ? "
        "WHERE exercise_id = ?"
    )
    give_up = (
        "UPDATE exercise_state SET "
        "status = CASE WHEN status = 'solved' THEN status ELSE 'given_up' END, updated_at = ? "
        "WHERE exercise_id = ?"
    )
    insert_attempt = """INSERT INTO attempt
            (at, exercise_id, variant, answer, status, score, misconception, feedback, counted)
        VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)"""

    insert_reset = "INSERT INTO reset_event (at, exercise_id) VALUES (?, ?)"
    reset_attempts_one = (
        "UPDATE attempt SET reset_id = ? WHERE reset_id IS NULL AND exercise_id = ?"
    )
    reset_attempts_all = "UPDATE attempt SET reset_id = ? WHERE reset_id IS NULL"
    delete_state_one = "DELETE FROM exercise_state WHERE exercise_id = ?"
    delete_state_all = "DELETE FROM exercise_state"

    # The newest `limit` attempts (-1: all), returned oldest first by the outer query.
    _attempt_cols = (
        "a.id, a.at, a.exercise_id, a.variant, a.answer, a.status, a.score, "
        "a.misconception, a.feedback, a.counted, r.at AS reset_at"
    )
    attempts_one = f"""SELECT * FROM (
            SELECT {_attempt_cols} FROM attempt a LEFT JOIN reset_event r ON r.id = a.reset_id
            WHERE a.exercise_id = ? ORDER BY a.id DESC LIMIT ?
        ) ORDER BY id"""
    attempts_all = f"""SELECT * FROM (
            SELECT {_attempt_cols} FROM attempt a LEFT JOIN reset_event r ON r.id = a.reset_id
            ORDER BY a.id DESC LIMIT ?
        ) ORDER BY id"""


_META_SEED = "learner_seed"
_META_CURRENT = "current"

# SQLite primary result codes (the low byte of an extended code), used to classify failures.
_SQLITE_PERM = 3
_SQLITE_BUSY = 5
_SQLITE_LOCKED = 6
_SQLITE_READONLY = 8
_SQLITE_IOERR = 10
_SQLITE_CORRUPT = 11
_SQLITE_FULL = 13
_SQLITE_CANTOPEN = 14
_SQLITE_NOTADB = 26


# --------------------------------------------------------------------------------------------
# Public value types
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ExerciseState:
    """Where a learner stands on one exercise.

    ``attempts`` counts only attempts whose verdict ``counts_as_attempt`` (not ``invalid`` or
    ``error``). ``solved_at`` is the UTC ISO time of the first solve since the last reset;
    ``updated_at`` the time of the last change (``None`` for an exercise never touched).
    """

    exercise_id: str
    status: ExerciseStatus
    attempts: int
    hints_shown: int
    solved_at: str | None
    updated_at: str | None

    @property
    def solved(self) -> bool:
        return self.status == "solved"

    @classmethod
    def fresh(cls, exercise_id: str) -> ExerciseState:
        """The state of an exercise the learner has not touched (or that was reset)."""
        return cls(exercise_id, "pending", 0, 0, None, None)


@dataclass(frozen=True)
class Attempt:
    """One checked answer, as logged (a row of the ``attempt`` table).

    ``variant`` is the variant seed the answer was checked against (0: canonical variant);
    ``counted`` whether it used up an attempt; ``reset_at`` the UTC ISO time of the reset that
    cleared it from the exercise's state, or ``None`` if it still counts.
    """

    id: int
    at: str
    exercise_id: str
    variant: int
    answer: str
    status: Status
    score: float
    misconception: str | None
    feedback: str
    counted: bool
    reset_at: str | None


# --------------------------------------------------------------------------------------------
# Locations
# --------------------------------------------------------------------------------------------


def variant_seed_for(learner_seed: int, exercise_id: str) -> int:
    """The variant seed a learner with ``learner_seed`` is given for ``exercise_id`` (see
    :meth:`Progress.variant_seed`); the batch grader recomputes it to detect edited seeds."""
    import random

    stream = random.Random(f"{learner_seed}\x00{exercise_id}")
    return 1 + stream.getrandbits(62) % VARIANT_MAX


def default_db_path() -> Path:
    """``<default_home()>/progress.sqlite3``."""
    return default_home() / DB_FILENAME


# --------------------------------------------------------------------------------------------
# Error messages
# --------------------------------------------------------------------------------------------


def _corrupt_error(path: Path, detail: str) -> ProgressError:
    return ProgressError(
        f"{path} is not a readable slamcourse progress database ({detail}). Move it aside "
        f"(e.g. rename it to {path.name}.bak) and slamcourse will start a new one; your old "
        "attempts stay in the moved file."
    )


def _newer_error(path: Path, version: int) -> ProgressError:
    return ProgressError(
        f"{path} was written by a newer slamcourse (schema {version}, this version knows up to "
        f"{SCHEMA_VERSION}); upgrade slamcourse (pip install -U slamcourse) or set "
        "SLAMCOURSE_HOME to use another progress folder."
    )


def _unwritable_error(path: Path, detail: str) -> ProgressError:
    return ProgressError(
        f"cannot write the progress database {path} ({detail}). Make sure the file and its "
        f"folder {path.parent} exist and are writable by you (check their permissions and free "
        "disk space), or set SLAMCOURSE_HOME to a writable folder."
    )


def _busy_error(path: Path, detail: str) -> ProgressError:
    return ProgressError(
        f"the progress database {path} is busy ({detail}): another slamcourse process has held "
        f"it for more than {BUSY_TIMEOUT_S:g} s. Finish or close the other slamcourse session "
        "and try again."
    )


def _translate(path: Path, exc: sqlite3.Error) -> ProgressError:
    """Turn an sqlite3 failure into a ProgressError naming the file and the fix."""
    code = getattr(exc, "sqlite_errorcode", None)
    primary = code & 0xFF if isinstance(code, int) else None
    detail = str(exc) or type(exc).__name__
    if primary in (_SQLITE_NOTADB, _SQLITE_CORRUPT):
        return _corrupt_error(path, detail)
    if primary in (_SQLITE_BUSY, _SQLITE_LOCKED):
        return _busy_error(path, detail)
    if primary in (_SQLITE_READONLY, _SQLITE_CANTOPEN, _SQLITE_PERM, _SQLITE_IOERR, _SQLITE_FULL):
        return _unwritable_error(path, detail)
    if isinstance(exc, sqlite3.OperationalError) or type(exc) is sqlite3.DatabaseError:
        # E.g. a missing table: the file is SQLite, but not a sound progress database.
        return _corrupt_error(path, detail)
    return ProgressError(f"the progress database {path} failed: {detail}")


def _storable(text: str | None) -> str | None:
    """``text`` as valid UTF-8 for SQLite: lone surrogates (undecodable bytes from ``argv``,
    ``"\\ud800"`` from JSON) become their ``\\udc80``-style escapes instead of failing the
    write. The engine refuses such answers as unreadable; the log still records what came in."""
    if text is None:
        return None
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return text.encode("utf-8", "backslashreplace").decode("utf-8")
    return text


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


# --------------------------------------------------------------------------------------------
# The store
# --------------------------------------------------------------------------------------------


class Progress:
    """A learner's progress store. Create it with :meth:`Progress.open`; close it when done.

    Usable as a context manager (``with Progress.open() as progress: ...``). Every method raises
    :class:`~slamcourse.errors.ProgressError` (never a raw ``sqlite3`` error) when the database
    cannot be used.
    """

    def __init__(self, path: Path, conn: sqlite3.Connection, learner_seed: int) -> None:
        """Internal: use :meth:`Progress.open`."""
        self._path = path
        self._conn: sqlite3.Connection | None = conn
        self._learner_seed = learner_seed
        self._lock = threading.RLock()
        # An in-memory copy of ``exercise_state`` (None: not read yet), so reading states costs
        # no query. This connection's own writes update it entry by entry after they commit;
        # a commit by any other connection (the terminal while the browser face runs, another
        # store on the same file) changes ``PRAGMA data_version``, and it is read again whole.
        self._mirror: dict[str, ExerciseState] | None = None
        self._data_version = -1
        self._revision = 0  # grows with every change of the mirror (see changes_since)
        self._complete_at = 0  # the revision of the last whole read (or reset of everything)
        self._changed_at: dict[str, int] = {}  # exercise id -> revision of its last change
        self._staged: list[tuple[str | None, ExerciseState | None]] | None = None

    # -- opening ---------------------------------------------------------------------------

    @classmethod
    def open(cls, path: Path | None = None) -> Progress:
        """Open (creating if missing) the progress database at ``path``.

        ``path`` defaults to :func:`default_db_path`. Creates the parent folders, checks that an
        existing file is a sound progress database no newer than this code, applies pending
        schema migrations and creates the learner seed on first use. An existing file that
        fails these checks is left untouched and reported as a ProgressError.
        """
        path = Path(path) if path is not None else default_db_path()
        path = path.expanduser().absolute()
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ProgressError(
                f"cannot create the progress folder {path.parent} ({exc.strerror or exc}). "
                "Create it yourself or set SLAMCOURSE_HOME to a writable folder."
            ) from exc
        if path.is_dir():
            raise ProgressError(
                f"{path} is a folder, not a progress database. Move it aside or set "
                "SLAMCOURSE_HOME to another folder."
            )
        try:
            existed = path.stat().st_size > 0
        except FileNotFoundError:
            existed = False
        except OSError as exc:
            raise _unwritable_error(path, exc.strerror or str(exc)) from exc

        try:
            # isolation_level=None: no implicit transactions; writes use BEGIN IMMEDIATE below.
            # check_same_thread=False: a server uses one store from several threads; every use of
            # the connection holds ``self._lock``, so calls are serialised.
            conn = sqlite3.connect(
                path, timeout=BUSY_TIMEOUT_S, isolation_level=None, check_same_thread=False
            )
        except sqlite3.Error as exc:
            raise _translate(path, exc) from exc
        try:
            seed = cls._prepare(path, conn, existed)
        except BaseException:
            conn.close()
            raise
        return cls(path, conn, seed)

    @staticmethod
    def _prepare(path: Path, conn: sqlite3.Connection, existed: bool) -> int:
        """Check, migrate and seed a freshly opened connection; return the learner seed.

        Reads come first, so a file that is rejected has not been written to.
        """
        try:
            conn.execute(_SQL.foreign_keys_on)
            version = int(conn.execute(_SQL.user_version).fetchone()[0])
            if existed:
                problems = [str(r[0]) for r in conn.execute(_SQL.quick_check).fetchmany(3)]
                if problems != ["ok"]:
                    raise _corrupt_error(path, "integrity check: " + "; ".join(problems))
            if version > SCHEMA_VERSION:
                raise _newer_error(path, version)
            if version == 0 and conn.execute(_SQL.count_schema_objects).fetchone()[0]:
                raise _corrupt_error(path, "an SQLite database of some other program")
            for target in range(version + 1, SCHEMA_VERSION + 1):
                with conn:
                    conn.execute(_SQL.begin)
                    # Re-read inside the lock: another process may have migrated meanwhile.
                    if int(conn.execute(_SQL.user_version).fetchone()[0]) >= target:
                        continue
                    for statement in _MIGRATIONS[target - 1]:
                        conn.execute(statement)
                    conn.execute(_SQL.set_user_version.format(target))
            row = conn.execute(_SQL.get_meta, (_META_SEED,)).fetchone()
            if row is None:
                import secrets  # only needed once per learner

                with conn:
                    conn.execute(_SQL.begin)
                    conn.execute(_SQL.add_meta, (_META_SEED, str(1 + secrets.randbelow(2**62))))
                row = conn.execute(_SQL.get_meta, (_META_SEED,)).fetchone()
            return int(row[0])
        except sqlite3.Error as exc:
            raise _translate(path, exc) from exc
        except ValueError as exc:  # a learner_seed that is not an integer
            raise _corrupt_error(path, f"bad learner seed: {exc}") from exc

    # -- plumbing ----------------------------------------------------------------------------

    @property
    def path(self) -> Path:
        """The database file."""
        return self._path

    def _db(self) -> sqlite3.Connection:
        if self._conn is None:
            raise ProgressError(f"the progress database {self._path} was already closed")
        return self._conn

    @contextmanager
    def _read(self) -> Iterator[sqlite3.Connection]:
        with self._lock:
            conn = self._db()
            try:
                yield conn
            except sqlite3.Error as exc:
                raise _translate(self._path, exc) from exc

    @contextmanager
    def _write(self) -> Iterator[sqlite3.Connection]:
        """One transaction: committed if the block succeeds, rolled back otherwise. The states
        the block staged (:meth:`_stage`) reach the mirror only once it committed, under the
        same hold of the lock, so the mirror follows the commits in their order."""
        with self._lock:
            conn = self._db()
            staged: list[tuple[str | None, ExerciseState | None]] = []
            self._staged = staged
            try:
                with conn:
                    conn.execute(_SQL.begin)
                    yield conn
            except sqlite3.Error as exc:
                raise _translate(self._path, exc) from exc
            finally:
                self._staged = None
            for exercise_id, state in staged:
                self._apply(exercise_id, state)

    def _stage(self, exercise_id: str | None, state: ExerciseState | None) -> None:
        """Inside :meth:`_write`: once committed, ``exercise_id``'s state is ``state`` (None:
        no row, i.e. fresh); ``exercise_id`` None: every row was deleted."""
        assert self._staged is not None, "_stage outside a write"
        self._staged.append((exercise_id, state))

    def _apply(self, exercise_id: str | None, state: ExerciseState | None) -> None:
        self._revision += 1
        if exercise_id is None:  # every state deleted
            if self._mirror is not None:
                self._mirror = {}
            self._complete_at = self._revision
            self._changed_at.clear()
            return
        if self._mirror is not None:
            if state is None:
                self._mirror.pop(exercise_id, None)
            else:
                self._mirror[exercise_id] = state
        self._changed_at[exercise_id] = self._revision

    def _synced(self, conn: sqlite3.Connection) -> dict[str, ExerciseState]:
        """The mirror, read again whole if it was never read or another connection committed
        since (``PRAGMA data_version`` is read first, so a commit racing the read only causes
        one more read next time). Call with the lock held."""
        version = int(conn.execute(_SQL.data_version).fetchone()[0])
        if self._mirror is None or version != self._data_version:
            self._mirror = {
                state.exercise_id: state
                for state in map(self._row_to_state, conn.execute(_SQL.all_states))
            }
            self._data_version = version
            self._revision += 1
            self._complete_at = self._revision
            self._changed_at.clear()
        return self._mirror

    def close(self) -> None:
        """Close the database. Safe to call twice."""
        if self._conn is not None:
            conn, self._conn = self._conn, None
            conn.close()

    def __enter__(self) -> Progress:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"Progress({str(self._path)!r})"

    # -- seeds -------------------------------------------------------------------------------

    @property
    def learner_seed(self) -> int:
        """This learner's random seed, created at first open and kept for good."""
        return self._learner_seed

    def variant_seed(self, exercise_id: str) -> int:
        """The learner's variant of ``exercise_id``: stable, in ``[1, 2**31 - 1]``, never 0.

        Derived from (learner seed, exercise id) by ``random.Random`` seeded with a string
        (SHA-512 based, the same on every platform and Python version), so it survives
        restarts and differs between learners and between exercises. (Not ``hashlib``: loading
        OpenSSL would cost every command a few milliseconds.)
        """
        return variant_seed_for(self._learner_seed, exercise_id)

    # -- exercise state ----------------------------------------------------------------------

    @staticmethod
    def _row_to_state(row: tuple[object, ...]) -> ExerciseState:
        exercise_id, status, attempts, hints, solved_at, updated_at = row
        return ExerciseState(
            exercise_id=str(exercise_id),
            status=cast(ExerciseStatus, status),
            attempts=int(cast(int, attempts)),
            hints_shown=int(cast(int, hints)),
            solved_at=cast("str | None", solved_at),
            updated_at=cast("str | None", updated_at),
        )

    @classmethod
    def _fetch_state(cls, conn: sqlite3.Connection, exercise_id: str) -> ExerciseState:
        row = conn.execute(_SQL.get_state, (exercise_id,)).fetchone()
        return ExerciseState.fresh(exercise_id) if row is None else cls._row_to_state(row)

    def state(self, exercise_id: str) -> ExerciseState:
        """The learner's state on ``exercise_id`` (pending with zeros if never touched)."""
        with self._read() as conn:
            state = self._synced(conn).get(exercise_id)
        return ExerciseState.fresh(exercise_id) if state is None else state

    def states(self) -> dict[str, ExerciseState]:
        """The state of every exercise touched since its last reset, by exercise id (ordered by
        id; a new dict each call)."""
        with self._read() as conn:
            mirror = self._synced(conn)
            return {key: mirror[key] for key in sorted(mirror)}

    def changes_since(self, revision: int | None) -> tuple[int, dict[str, ExerciseState], bool]:
        """What changed since ``revision`` (a value this method returned; None: nothing known
        yet), for a reader that keeps its own copy up to date (the engine's summary):
        ``(new revision, states, complete)``. ``complete``: ``states`` is every state (an
        exercise not in it is fresh), as :meth:`states` returns; else ``states`` holds only
        the exercises changed since ``revision``, each at its state now (fresh if reset)."""
        with self._read() as conn:
            mirror = self._synced(conn)
            now = self._revision
            if revision is None or revision < self._complete_at or revision > now:
                return now, {key: mirror[key] for key in sorted(mirror)}, True
            changed = sorted(e for e, at in self._changed_at.items() if at > revision)
            return (
                now,
                {e: mirror.get(e) or ExerciseState.fresh(e) for e in changed},
                False,
            )

    def record_attempt(
        self,
        exercise_id: str,
        variant: int,
        answer: str,
        verdict: Verdict,
        *,
        practice: bool = False,
    ) -> ExerciseState:
        """Log an answer and its verdict, and update the exercise's state; return the new state.

        In one transaction: the attempt is appended to the log; ``attempts`` grows only if
        ``verdict.counts_as_attempt``; a passing verdict makes the exercise ``solved`` (and it
        stays solved after later failures; ``solved_at`` keeps the first solve's time).
        A ``practice`` attempt (the lesson's own numbers) is logged, never counted, and leaves
        the state as it was.
        """
        now = _now()
        counted = int(verdict.counts_as_attempt and not practice)
        with self._write() as conn:
            conn.execute(
                _SQL.insert_attempt,
                (
                    now,
                    exercise_id,
                    int(variant),
                    _storable(answer),
                    verdict.status,
                    float(verdict.score),
                    _storable(verdict.misconception),
                    _storable(verdict.feedback),
                    counted,
                ),
            )
            if practice:
                return self._fetch_state(conn, exercise_id)
            conn.execute(_SQL.ensure_state, (exercise_id, now))
            conn.execute(_SQL.apply_attempt, (counted, int(verdict.passed), now, exercise_id))
            state = self._fetch_state(conn, exercise_id)
            self._stage(exercise_id, state)
            return state

    def reveal_hint(self, exercise_id: str) -> int:
        """Count one more hint shown for ``exercise_id``; return the new number of hints shown."""
        now = _now()
        with self._write() as conn:
            conn.execute(_SQL.ensure_state, (exercise_id, now))
            conn.execute(_SQL.add_hint, (now, exercise_id))
            state = self._fetch_state(conn, exercise_id)
            self._stage(exercise_id, state)
            return state.hints_shown

    def give_up(self, exercise_id: str) -> ExerciseState:
        """Mark ``exercise_id`` as given up (unless already solved); return the new state.

        A given-up exercise shows its explanation and ``next`` moves past it; solving it later
        still makes it ``solved``.
        """
        now = _now()
        with self._write() as conn:
            conn.execute(_SQL.ensure_state, (exercise_id, now))
            conn.execute(_SQL.give_up, (now, exercise_id))
            state = self._fetch_state(conn, exercise_id)
            self._stage(exercise_id, state)
            return state

    # -- current exercise --------------------------------------------------------------------

    def current(self) -> str | None:
        """The exercise pinned by ``goto``, or ``None``."""
        with self._read() as conn:
            row = conn.execute(_SQL.get_meta, (_META_CURRENT,)).fetchone()
        return None if row is None else str(row[0])

    def set_current(self, exercise_id: str | None) -> None:
        """Pin ``exercise_id`` as the current exercise; ``None`` unpins."""
        with self._write() as conn:
            if exercise_id is None:
                conn.execute(_SQL.del_meta, (_META_CURRENT,))
            else:
                conn.execute(_SQL.set_meta, (_META_CURRENT, exercise_id))

    # -- engine-owned values (navigation: the `next` pointer, skipped exercises) ---------------

    def meta(self, key: str) -> str | None:
        """A value the engine keeps in ``meta`` (e.g. its ``next`` pointer), or ``None``."""
        with self._read() as conn:
            row = conn.execute(_SQL.get_meta, (key,)).fetchone()
        return None if row is None else str(row[0])

    def set_meta(self, values: dict[str, str | None]) -> None:
        """Set (``None``: delete) values in ``meta``, in one transaction; never the seed."""
        if _META_SEED in values:
            raise ValueError("the learner seed is never rewritten")
        with self._write() as conn:
            for key, value in values.items():
                if value is None:
                    conn.execute(_SQL.del_meta, (key,))
                else:
                    conn.execute(_SQL.set_meta, (key, value))

    # -- reset and history -------------------------------------------------------------------

    def reset(self, exercise_id: str | None = None) -> None:
        """Forget the state of ``exercise_id`` (or of every exercise, and the pinned current one).

        The attempt log is append-only: attempts are kept, stamped with this reset (see
        :attr:`Attempt.reset_at`), and the reset itself is recorded. The learner seed, and so
        every variant, stays the same.
        """
        with self._write() as conn:
            reset_id = conn.execute(_SQL.insert_reset, (_now(), exercise_id)).lastrowid
            if exercise_id is None:
                conn.execute(_SQL.reset_attempts_all, (reset_id,))
                conn.execute(_SQL.delete_state_all)
                conn.execute(_SQL.del_meta, (_META_CURRENT,))
            else:
                conn.execute(_SQL.reset_attempts_one, (reset_id, exercise_id))
                conn.execute(_SQL.delete_state_one, (exercise_id,))
            self._stage(exercise_id, None)

    def attempts(self, exercise_id: str | None = None, limit: int | None = None) -> list[Attempt]:
        """Logged attempts, oldest first, including those cleared by a reset.

        ``exercise_id`` restricts to one exercise; ``limit`` keeps only the newest ``limit``.
        """
        bound = -1 if limit is None else max(0, int(limit))
        with self._read() as conn:
            if exercise_id is None:
                rows = conn.execute(_SQL.attempts_all, (bound,)).fetchall()
            else:
                rows = conn.execute(_SQL.attempts_one, (exercise_id, bound)).fetchall()
        return [
            Attempt(
                id=int(r[0]),
                at=str(r[1]),
                exercise_id=str(r[2]),
                variant=int(r[3]),
                answer=str(r[4]),
                status=cast(Status, r[5]),
                score=float(r[6]),
                misconception=r[7],
                feedback=str(r[8]),
                counted=bool(r[9]),
                reset_at=r[10],
            )
            for r in rows
        ]
