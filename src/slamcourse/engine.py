"""The engine: the one boundary every face (terminal, browser, batch grader) talks to.

It ties the course (what to ask), the kinds (how to grade), the sandbox workers (where learner
code runs) and the progress store (what happened) together, and owns every rule a face needs:

- a learner gets their own variant; the canonical variant (the lesson's own numbers) is
  *practice*: graded and logged, never the learner's solve and never a counted attempt;
- the explanation is shown only once an exercise is solved or given up (:class:`Locked`);
- after repeated misses with no hint taken, a result carries a nudge towards the hints;
- an unreadable answer (or a grader fault) costs no attempt.

It never prints, never reads the environment (:class:`~slamcourse.settings.Settings` does) and
returns data: :class:`Prompt`, :class:`Result`, :class:`Hint`, each with ``to_dict()``.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from slamcourse.course import templates, variants
from slamcourse.course.loader import Course, chapter_segments, load_course
from slamcourse.course.locate import course_root
from slamcourse.course.model import ExerciseSpec, Variant
from slamcourse.errors import UsageError
from slamcourse.kinds import get_kind
from slamcourse.progress import ExerciseState, Progress
from slamcourse.settings import Settings, activate_cache, cache_dir
from slamcourse.verdict import Verdict

if TYPE_CHECKING:
    from collections.abc import Callable

    from slamcourse.course.model import Chapter
    from slamcourse.grading.pool import WorkerPool

NUDGE_AFTER = 2
"""Counted misses, with no hint taken, after which a result suggests a hint."""

STATUS_MARK = {"solved": "✓", "given_up": "⚐", "pending": "○", "skipped": "↷"}
"""The one mark of each exercise state, in every face (``skipped``: pending, passed over)."""
STATUS_WORD = {"solved": "solved", "given_up": "given up", "pending": "open", "skipped": "skipped"}
"""The one word of each exercise state, in every face."""


class Locked(UsageError):
    """The explanation of an exercise is asked for before it is solved or given up.

    Fix: solve the exercise, or give up on it to see the worked explanation.
    """


class FileChanged(UsageError):
    """A code exercise's file changed on disk since the editor that sent a new text loaded it;
    nothing was written.

    Fix: load the file's version into the editor, or keep the editor's text (send it again
    based on the file's version, :attr:`disk_hash`, which overwrites the file).
    """

    def __init__(self, exercise_id: str, path: Path, disk_source: str, disk_hash: str) -> None:
        super().__init__(
            f"{path.name} changed on disk since the editor loaded it, so nothing was written: "
            "load the file's version, or keep yours (overwrite the file)"
        )
        self.exercise_id = exercise_id
        self.path = path
        self.disk_source = disk_source
        self.disk_hash = disk_hash

    def to_dict(self) -> dict[str, Any]:
        return {
            "exercise": self.exercise_id,
            "file": str(self.path),
            "name": self.path.name,
            "message": str(self),
            "disk_source": self.disk_source,
            "disk_hash": self.disk_hash,
        }


# ------------------------------------------------------------------------------ results


@dataclass(frozen=True)
class ChapterInfo:
    id: str
    number: int
    title: str
    summary: str
    exercise_ids: tuple[str, ...]


@dataclass(frozen=True)
class Segment:
    """Chapter prose (Markdown with ``$…$`` math) and the exercise placed after it, if any."""

    markdown: str
    exercise_id: str | None


@dataclass(frozen=True)
class Prompt:
    """Everything a face needs to pose one exercise.

    ``text`` is the prompt as Markdown with ``$…$`` math; ``form`` the expected input as data
    (``{"type": "matrix", "rows": 3, "cols": 3}``, choices, listing lines, …; computed on first
    use, since a vector's length comes from the reference answer).
    """

    exercise_id: str
    title: str
    kind: str
    chapter_id: str
    chapter_number: int
    chapter_title: str
    position: tuple[int, int]  # (index of the exercise in its chapter, from 1; count)
    variant: Variant
    practice: bool  # the canonical variant of an exercise that has variants
    text: str
    how_to_answer: str
    tolerance: dict[str, Any] | None
    status: str
    attempts: int
    hints_shown: tuple[str, ...]
    hints_total: int
    code_file: Path | None
    _form: Callable[[], dict[str, Any]] = field(repr=False, compare=False)

    @cached_property
    def form(self) -> dict[str, Any]:
        return self._form()

    def to_dict(self) -> dict[str, Any]:
        form = dict(self.form)
        if self.code_file is not None:
            form["file"] = str(self.code_file)
        return {
            "exercise": self.exercise_id,
            "title": self.title,
            "kind": self.kind,
            "chapter": {
                "id": self.chapter_id,
                "number": self.chapter_number,
                "title": self.chapter_title,
            },
            "position": list(self.position),
            "variant": self.variant.seed,
            "canonical": self.variant.seed == 0,
            "practice": self.practice,
            "text": self.text,
            "form": form,
            "how_to_answer": self.how_to_answer,
            "tolerance": self.tolerance,
            "status": self.status,
            "attempts": self.attempts,
            "hints": {"shown": list(self.hints_shown), "total": self.hints_total},
        }


@dataclass(frozen=True)
class Result:
    """The outcome of one submission: the verdict plus what the engine's rules add to it."""

    exercise_id: str
    variant: int
    verdict: Verdict
    practice: bool
    counted: bool  # an attempt was used up
    explanation: str | None  # only once passed
    nudge: str | None
    exercise_status: str
    attempts: int

    @property
    def passed(self) -> bool:
        return self.verdict.passed

    @property
    def exit_code(self) -> int:
        return self.verdict.exit_code

    @property
    def tests(self) -> list[dict[str, Any]]:
        """Per-test details: one entry for the failing input of a code exercise, if any."""
        d = self.verdict.details
        if "examples" not in d:
            return []
        if "input" not in d:
            return [{"name": f"{d['examples']} property-test inputs", "status": "passed"}]
        return [
            {
                "name": "smallest failing input",
                "status": "timeout" if self.verdict.status == "timeout" else "failed",
                "input": d.get("input"),
                "expected": d.get("expected"),
                "got": d.get("got"),
                "message": self.verdict.feedback,
            }
        ]

    def to_dict(self) -> dict[str, Any]:
        v = self.verdict
        return {
            "exercise": self.exercise_id,
            "variant": self.variant,
            "practice": self.practice,
            "status": v.status,
            "score": v.score,
            "counted": self.counted,
            "feedback": v.feedback,
            "misconception": v.misconception,
            "details": v.details,
            "tests": self.tests,
            "explanation": self.explanation,
            "nudge": self.nudge,
            "exercise_status": self.exercise_status,
            "attempts": self.attempts,
        }


@dataclass(frozen=True)
class NextStep:
    """Which exercise ``next`` poses, and why: the faces show :attr:`note` as it is.

    The rule (:meth:`Engine.next_step`): after an exercise is solved or given up (or skipped),
    the next open exercise after it in its chapter, then in the following chapters, then
    wrapping to the earliest open one; skipped exercises are passed over (and named) until only
    they remain. ``goto`` pins an exercise, which is posed whatever its status.
    """

    exercise_id: str | None  # None: every exercise is solved or given up
    after: str | None  # the exercise it follows (None: pinned by goto, or from the start)
    pinned: bool  # asked for by goto
    status: str  # the posed exercise's status (a pinned one may be solved)
    wrapped: bool  # past the end of the course, back to the earliest open exercise
    passed_over: tuple[str, ...]  # skipped exercises passed over on the way
    only_skipped: bool  # every open exercise left was skipped: back to one of them

    @property
    def note(self) -> str | None:
        """What a face says before posing it (Markdown), or None when it is simply next."""
        ex = self.exercise_id
        if ex is None:
            return None
        parts = []
        if self.pinned and self.status == "solved":
            parts.append(
                f"`{ex}` is already solved; it is posed again as asked (answers are graded as "
                "usual, and it stays solved)."
            )
        elif self.pinned and self.status == "given_up":
            parts.append(
                f"`{ex}` was given up; it is posed again as asked (solving it now marks it solved)."
            )
        if self.passed_over:
            n = len(self.passed_over)
            names = ", ".join(f"`{e}`" for e in self.passed_over)
            parts.append(f"Passing over {n} skipped exercise{'s' if n != 1 else ''}: {names}.")
        if self.only_skipped:
            parts.append(f"Only skipped exercises are left: back to `{ex}`.")
        elif self.wrapped:
            parts.append(
                f"No open exercise after `{self.after}`: back to the earliest open one, `{ex}`."
            )
        return " ".join(parts) or None

    def to_dict(self) -> dict[str, Any]:
        return {
            "exercise": self.exercise_id,
            "after": self.after,
            "pinned": self.pinned,
            "status": self.status,
            "wrapped": self.wrapped,
            "passed_over": list(self.passed_over),
            "only_skipped": self.only_skipped,
            "note": self.note,
        }


@dataclass(frozen=True)
class Hint:
    number: int
    total: int
    text: str | None  # None when there are no more hints

    def to_dict(self) -> dict[str, Any]:
        return {"number": self.number, "total": self.total, "hint": self.text}


# ------------------------------------------------------------------------------ the engine


class Engine:
    """A course, a learner's progress (optional) and the sandbox workers, behind one API.

    Thread-safe for a server: progress calls are serialised by the store, workers are spawned
    from one long-lived thread of the pool.
    """

    def __init__(
        self, course: Course, settings: Settings, progress: Progress | None = None
    ) -> None:
        self.course = course
        self.settings = settings
        self.progress = progress
        self._pool: WorkerPool | None = None
        self._fork_workers = False
        self._pool_lock = threading.Lock()
        self._nav_lock = threading.Lock()  # skipped: read, change, write
        self._summary = _SummaryCache()
        self._cache_before: Path | None = None  # the cache in use before this engine opened

    @classmethod
    def open(
        cls,
        settings: Settings | None = None,
        *,
        with_progress: bool = True,
        warm_sandbox: bool = False,
        fork_workers: bool = False,
        course: Course | None = None,
    ) -> Engine:
        """Open the course and (``with_progress``) the learner's progress.

        ``warm_sandbox``: start a sandbox worker first, so its interpreter imports numpy while
        this process loads the course (a one-shot code check). ``fork_workers``: every code
        check gets a fresh worker forked from one sandboxed zygote of this engine (a batch
        grader's engine, which serves one submission and checks many exercises); when the
        engine closes, the zygote is reset and kept for the next such engine of this process,
        or closed if it cannot be (see :class:`~slamcourse.grading.pool.WorkerPool`).
        ``course``: the course already loaded from ``settings.course`` (a batch loads it once
        per process; its exercises are parsed once, not once per submission).
        """
        settings = settings or Settings.from_env()
        before = cache_dir()
        activate_cache(settings.cache)
        engine_pool = None
        if warm_sandbox:
            engine_pool = cls._new_pool(
                settings, keep_spare=False, fork=fork_workers, reuse=fork_workers
            )
            engine_pool.warm()
        try:
            if course is None:
                course = load_course(course_root(settings.course))
            progress = Progress.open(settings.home / "progress.sqlite3") if with_progress else None
        except BaseException:
            activate_cache(before)
            if engine_pool is not None:
                engine_pool.close()
            raise
        engine = cls(course, settings, progress)
        engine._pool = engine_pool
        engine._fork_workers = fork_workers
        engine._cache_before = before
        return engine

    @staticmethod
    def _new_pool(
        settings: Settings, *, keep_spare: bool, fork: bool = False, reuse: bool = False
    ) -> WorkerPool:
        from slamcourse.grading.pool import WorkerPool

        return WorkerPool(
            require_isolation=settings.require_isolation,
            keep_spare=keep_spare,
            fork=fork,
            reuse=reuse,
        )

    def start_workers(self) -> None:
        """For long-running faces (one learner's home: the browser, ``watch``, ``next``): code
        checks get fresh workers forked from one sandboxed zygote, the next one forked ahead,
        so a check pays no interpreter start and a burst of checks does not starve the
        server's other requests of CPU."""
        with self._pool_lock:
            if self._pool is None or not self._pool.fork:
                old, self._pool = (
                    self._pool,
                    self._new_pool(self.settings, keep_spare=True, fork=True),
                )
                if old is not None:
                    old.close()
            self._pool.warm()

    def close(self) -> None:
        if cache_dir() == self.settings.cache:  # (a batch deletes a submission's home after
            activate_cache(self._cache_before)  # its engine: nothing may be cached there)
        if self.progress is not None:
            self.progress.close()
        with self._pool_lock:
            pool, self._pool = self._pool, None
        if pool is not None:
            pool.close()

    def __enter__(self) -> Engine:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ---------------------------------------------------------------- the course
    def exercise(self, exercise_id: str) -> ExerciseSpec:
        return self.course.exercise(exercise_id)

    def is_code(self, exercise_id: str) -> bool:
        return self.exercise(exercise_id).kind == "code"

    def chapters(self) -> list[ChapterInfo]:
        return [
            ChapterInfo(ch.id, ch.number, ch.title, ch.summary, tuple(ch.exercises))
            for ch in self.course.chapters
        ]

    def chapter_segments(self, chapter_id: str) -> list[Segment]:
        chapter = self.course.chapter(chapter_id)
        return [Segment(prose, ex) for ex, prose in chapter_segments(chapter)]

    def context(self, exercise_id: str) -> str:
        """The chapter prose that leads up to this exercise (Markdown)."""
        chapter = self.course.chapter_of(exercise_id)
        for ex_id, prose in chapter_segments(chapter):
            if ex_id == exercise_id:
                return prose.strip()
        return ""

    # ---------------------------------------------------------------- variants
    def variant(
        self, exercise_id: str, *, canonical: bool = False, seed: int | None = None
    ) -> Variant:
        """The learner's own variant, or the canonical one (0), or variant ``seed``."""
        spec = self.exercise(exercise_id)
        if seed is not None and seed < 0:
            raise UsageError("a variant seed is a whole number ≥ 0 (0 is the canonical variant)")
        if canonical:
            chosen = 0
        elif seed is not None:
            chosen = seed
        elif self.progress is not None and spec.has_variants:
            chosen = self.progress.variant_seed(exercise_id)
        else:
            chosen = 0
        return variants.variant(spec, chosen)

    def _practice(self, spec: ExerciseSpec, variant: Variant) -> bool:
        """Not the learner's own variant: graded and logged, never a solve or an attempt."""
        if not spec.has_variants:
            return False
        own = self.progress.variant_seed(spec.id) if self.progress is not None else None
        return variant.seed != own

    # ---------------------------------------------------------------- posing
    def pose(self, exercise_id: str, *, canonical: bool = False, seed: int | None = None) -> Prompt:
        spec = self.exercise(exercise_id)
        variant = self.variant(exercise_id, canonical=canonical, seed=seed)
        kind = get_kind(spec.kind)
        chapter = self.course.chapter_of(exercise_id)
        state = self.progress.state(exercise_id) if self.progress is not None else None
        shown = state.hints_shown if state is not None else 0
        code_file = self.code_file(exercise_id) if spec.kind == "code" else None
        return Prompt(
            exercise_id=exercise_id,
            title=spec.title,
            kind=spec.kind,
            chapter_id=chapter.id,
            chapter_number=chapter.number,
            chapter_title=chapter.title,
            position=(chapter.exercises.index(exercise_id) + 1, len(chapter.exercises)),
            variant=variant,
            practice=self._practice(spec, variant),
            text=templates.render(spec, spec.prompt, dict(variant.params)),
            how_to_answer=kind.how_to_answer(spec, variant),
            tolerance=_tolerance(spec),
            status=state.status if state is not None else "pending",
            attempts=state.attempts if state is not None else 0,
            hints_shown=tuple(
                templates.render(spec, h, dict(variant.params)) for h in spec.hints[:shown]
            ),
            hints_total=len(spec.hints),
            code_file=code_file,
            _form=lambda: kind.form(spec, variant),
        )

    def code_file(self, exercise_id: str) -> Path:
        """The learner's file of a code exercise, written from the starter when missing."""
        from slamcourse.workspace import ensure_starter

        spec = self.exercise(exercise_id)
        if spec.kind != "code":
            raise UsageError(f"{exercise_id} is a {spec.kind} exercise, not a code exercise")
        return ensure_starter(spec, self.settings.workspace)[0]

    def code_source(self, exercise_id: str) -> tuple[str, str]:
        """The learner's file of a code exercise as ``(text, content hash)``: what an editor
        shows, and the base it sends back with its text (:meth:`submit_edit`)."""
        from slamcourse.workspace import read_source_and_hash

        return read_source_and_hash(self.code_file(exercise_id))

    def submit_edit(
        self, exercise_id: str, source: str, *, based_on: str | None, overwrite: bool = False
    ) -> tuple[Result, str | None]:
        """An editor's check: save ``source`` to the learner's file, then grade ``source``
        itself (never the file read back, which another save may have replaced meanwhile).

        ``based_on``: the content hash of the file's text the editor loaded
        (:meth:`code_source`). If the file changed on disk since, nothing is written or graded
        and :class:`FileChanged` carries the file's version. ``overwrite``: save whatever the
        file holds. Neither: the source is graded and not saved (a client that never loaded
        the file cannot know what it would overwrite). Returns the result and the file's
        content hash after the save (None when not saved)."""
        from slamcourse.workspace import save_source

        path = self.code_file(exercise_id)
        saved_hash = None
        if based_on is not None or overwrite:
            try:
                source.encode("utf-8")
            except UnicodeEncodeError:
                pass  # not a text a file can hold: graded (unreadable), never saved
            else:
                saved = save_source(path, source, based_on=None if overwrite else based_on)
                if not saved.written:
                    raise FileChanged(exercise_id, path, saved.text, saved.hash)
                saved_hash = saved.hash
        return self.submit_code(exercise_id, source=source, path=path), saved_hash

    # ---------------------------------------------------------------- grading
    def submit(
        self, exercise_id: str, answer: str, *, canonical: bool = False, seed: int | None = None
    ) -> Result:
        """Grade a text answer (every kind but code)."""
        spec = self.exercise(exercise_id)
        if spec.kind == "code":
            raise UsageError(
                f"{exercise_id} is a code exercise: submit the source of "
                f"`{spec.options.function}`, not a text answer"
            )
        variant = self.variant(exercise_id, canonical=canonical, seed=seed)
        verdict = get_kind(spec.kind).check(spec, variant, answer)
        return self._conclude(spec, variant, answer, verdict)

    def submit_code(
        self,
        exercise_id: str,
        *,
        source: str | None = None,
        path: Path | None = None,
        hidden_seed: int | None = None,
        tests: Any = None,
    ) -> Result:
        """Grade learner code in the sandbox: ``source``, or the file ``path``, or (neither)
        the learner's workspace file. ``hidden_seed`` (grading mode; default: the settings')
        also runs inputs drawn with that secret seed. ``tests``: the exercise's test set built
        once for a whole batch (:class:`~slamcourse.grading.testset.SharedTests`); a batch
        grades without shrinking a failure (it reports the first failing input)."""
        import hashlib

        from slamcourse.kinds.code import read_source

        spec = self.exercise(exercise_id)
        if spec.kind != "code":
            raise UsageError(
                f"{exercise_id} is a {spec.kind} exercise: answer it with text, not code"
            )
        if source is None:
            path = path if path is not None else self.code_file(exercise_id)
            source = read_source(path)
        filename = path.name if path is not None else f"{spec.options.function}.py"
        verdict = get_kind("code").check_source(  # type: ignore[attr-defined]
            spec,
            source,
            filename,
            require_isolation=self.settings.require_isolation,
            spawn=self._take_worker,
            hidden_seed=hidden_seed if hidden_seed is not None else self.settings.hidden_seed,
            tests=tests,
            shrink=tests is None,
        )
        digest = hashlib.sha256(source.encode("utf-8", "replace")).hexdigest()[:16]
        where = str(path) if path is not None else filename
        return self._conclude(spec, variants.variant(spec, 0), f"{where} sha256:{digest}", verdict)

    def expect_code(self, answers: Sequence[tuple[str, str]]) -> None:
        """The code exercises this engine will grade next, in order, each with its source (a
        batch submission's): its pool forks each worker ahead with what the next one needs
        (:meth:`~slamcourse.grading.pool.WorkerPool.expect`)."""
        upcoming = []
        for exercise_id, source in answers:
            spec = self.exercise(exercise_id)
            if spec.kind == "code":
                upcoming.append(spec.options.worker_request(source))
        with self._pool_lock:
            pool = self._pool
        if pool is not None and pool.fork:
            pool.expect(upcoming)

    def _take_worker(self, limits: Any = None, *, scipy: bool = True) -> Any:
        """A fresh sandbox worker with ``limits`` (None: the defaults, which the pool's
        pre-started workers have) for code that does (not) use ``scipy``."""
        with self._pool_lock:
            if self._pool is None:
                self._pool = self._new_pool(
                    self.settings,
                    keep_spare=False,
                    fork=self._fork_workers,
                    reuse=self._fork_workers,
                )
            pool = self._pool
        return pool.take(limits, scipy=scipy)

    def _conclude(
        self, spec: ExerciseSpec, variant: Variant, answer: str, verdict: Verdict
    ) -> Result:
        """Apply the engine's rules to a verdict: record it, unlock the explanation, nudge."""
        practice = self._practice(spec, variant)
        state: ExerciseState | None = None
        if self.progress is not None and self.settings.record:
            state = self.progress.record_attempt(
                spec.id, variant.seed, answer, verdict, practice=practice
            )
        elif self.progress is not None:
            state = self.progress.state(spec.id)
        counted = verdict.counts_as_attempt and not practice and self.settings.record
        if self.progress is not None and self.settings.record and verdict.passed and not practice:
            self._point("after", spec.id)  # `next` goes on from here (NextStep)
        explanation = self._explanation(spec, variant) if verdict.passed else None
        nudge = None
        if (
            not verdict.passed
            and state is not None
            and counted
            and state.attempts >= NUDGE_AFTER
            and state.hints_shown == 0
            and spec.hints
        ):
            nudge = "Stuck? A hint is available."
        return Result(
            exercise_id=spec.id,
            variant=variant.seed,
            verdict=verdict,
            practice=practice,
            counted=counted,
            explanation=explanation,
            nudge=nudge,
            exercise_status=state.status if state is not None else "pending",
            attempts=state.attempts if state is not None else 0,
        )

    # ---------------------------------------------------------------- help
    def _explanation(self, spec: ExerciseSpec, variant: Variant) -> str:
        answer: Any = get_kind(spec.kind).expected(spec, variant)
        return templates.render(spec, spec.explanation, {**variant.params, "answer": answer})

    def explanation(self, exercise_id: str) -> str:
        """The worked explanation of the learner's variant, once solved or given up."""
        spec = self.exercise(exercise_id)
        if self._store().state(exercise_id).status == "pending":
            raise Locked(
                f"{exercise_id} is not solved yet: solve it first, or give up on it to see "
                "the worked explanation"
            )
        return self._explanation(spec, self.variant(exercise_id))

    def give_up(self, exercise_id: str) -> str:
        """Mark the exercise given up (unless solved) and return its explanation."""
        self.exercise(exercise_id)
        self._store().give_up(exercise_id)
        self._point("after", exercise_id)  # `next` goes on from here (NextStep)
        return self.explanation(exercise_id)

    def hint(self, exercise_id: str) -> Hint:
        """Reveal the next hint of the learner's variant."""
        spec = self.exercise(exercise_id)
        store = self._store()
        shown = store.state(exercise_id).hints_shown
        total = len(spec.hints)
        if shown >= total:
            return Hint(total, total, None)
        number = store.reveal_hint(exercise_id)
        variant = self.variant(exercise_id)
        text = templates.render(spec, spec.hints[number - 1], dict(variant.params))
        return Hint(number, total, text)

    # ---------------------------------------------------------------- progress
    def _store(self) -> Progress:
        if self.progress is None:
            raise UsageError("this needs the learner's progress, which is not open")
        return self.progress

    def state(self, exercise_id: str) -> ExerciseState:
        return self._store().state(exercise_id)

    # The `next` pointer lives in the store's meta as JSON: {"mode": "goto", "exercise": X}
    # (pose X, whatever its status) or {"mode": "after", "exercise": X} (X was just solved,
    # given up or skipped: pose the next open exercise after it). Writing it never needs the
    # chapter index, so `check` stays cheap; it is resolved only when `next` is asked.
    _POINTER = "pointer"
    _SKIPPED = "skipped"

    def _pointer(self) -> tuple[str, str] | None:
        import json

        store = self._store()
        raw = store.meta(self._POINTER)
        if raw is not None:
            try:
                data = json.loads(raw)
                return str(data["mode"]), str(data["exercise"])
            except (ValueError, KeyError, TypeError):
                return None
        legacy = store.current()  # pinned by an older slamcourse: posed while open
        return ("legacy", legacy) if legacy is not None else None

    def _point(self, mode: str, exercise_id: str, **more: str | None) -> None:
        import json

        value = json.dumps({"mode": mode, "exercise": exercise_id})
        self._store().set_meta({self._POINTER: value, "current": None, **more})

    def skipped(self) -> list[str]:
        """Exercises the learner skipped that are still open, in course order."""
        import json

        raw = self._store().meta(self._SKIPPED)
        try:
            ids = set(json.loads(raw)) if raw else set()
        except ValueError:
            ids = set()
        return [e for e in self.course.exercise_ids if e in ids and e in self._open_set()]

    def _open_set(self) -> set[str]:
        states = self._store().states()
        return {
            e for e in self.course.exercise_ids if e not in states or states[e].status == "pending"
        }

    def _skipped_value(self, add: str | None = None, drop: str | None = None) -> str | None:
        import json

        raw = self._store().meta(self._SKIPPED)
        try:
            ids = set(json.loads(raw)) if raw else set()
        except ValueError:
            ids = set()
        if add is not None:
            ids.add(add)
        if drop is not None:
            ids.discard(drop)
        return json.dumps(sorted(ids)) if ids else None

    def next_step(self) -> NextStep:
        """The exercise ``next`` poses (both faces ask this after every answer), with why."""
        order = self.course.exercise_ids
        states = self._store().states()

        def status(e: str) -> str:
            return states[e].status if e in states else "pending"

        open_ids = {e for e in order if status(e) == "pending"}
        pointer = self._pointer()
        if pointer is not None and pointer[1] in order:
            mode, at = pointer
            if mode == "goto" or (mode == "legacy" and at in open_ids):
                return NextStep(at, None, mode == "goto", status(at), False, (), False)
            start = order.index(at)
        else:
            at, start = None, -1
        skipped = set(self.skipped()) & open_ids
        ahead = order[start + 1 :] + order[: start + 1]
        passed: list[str] = []
        for e in ahead:
            if e in skipped:
                passed.append(e)
            elif e in open_ids:
                return NextStep(
                    e, at, False, "pending", order.index(e) <= start, tuple(passed), False
                )
        for e in ahead:
            if e in skipped:
                return NextStep(e, at, False, "pending", order.index(e) <= start, (), True)
        return NextStep(None, at, False, "pending", False, (), False)

    def next_exercise(self) -> str | None:
        """The exercise ``next`` poses (:meth:`next_step` without the why)."""
        return self.next_step().exercise_id

    def goto(self, exercise_id: str) -> NextStep:
        """Make ``exercise_id`` the exercise ``next`` poses, solved or not (no longer skipped)."""
        self.exercise(exercise_id)  # unknown ids are a usage error
        with self._nav_lock:
            self._point(
                "goto", exercise_id, **{self._SKIPPED: self._skipped_value(drop=exercise_id)}
            )
        return self.next_step()

    def skip(self, exercise_id: str) -> str | None:
        """Move past ``exercise_id`` without solving it: it stays open, and ``next`` passes over
        it (and says so) until only skipped exercises are left. Returns the next exercise."""
        self.exercise(exercise_id)
        with self._nav_lock:
            self._point(
                "after", exercise_id, **{self._SKIPPED: self._skipped_value(add=exercise_id)}
            )
        return self.next_exercise()

    def reset(self, exercise_id: str | None = None) -> None:
        if exercise_id is not None:
            self.exercise(exercise_id)
        store = self._store()
        with self._nav_lock:
            store.reset(exercise_id)
            if exercise_id is None:
                store.set_meta({self._POINTER: None, self._SKIPPED: None})
            else:
                store.set_meta({self._SKIPPED: self._skipped_value(drop=exercise_id)})

    def summary(self, step: NextStep | None = None) -> list[dict[str, Any]]:
        """Per chapter: id, number, title, solved/total, and each exercise with its status
        (and whether it is skipped, and whether it is the one ``next`` poses).

        Kept up to date, not recomputed (the browser asks for it with every answer): only the
        chapters holding an exercise whose state changed since the last call
        (:meth:`Progress.changes_since`), the old or new ``next`` exercise, or one newly skipped
        or no longer skipped are rebuilt. Always equal to :meth:`summary_full`. ``step``: the
        :meth:`next_step` the caller already asked for (not computed twice)."""
        if step is not None:
            current = step.exercise_id
        else:
            current = self.next_exercise() if self.progress else None
        skipped = frozenset(self.skipped()) if self.progress else frozenset()
        return self._summary.get(self, current, skipped)

    def summary_full(self) -> list[dict[str, Any]]:
        """:meth:`summary` recomputed from every state (what the kept one is tested against)."""
        states = self._store().states() if self.progress else {}
        current = self.next_exercise() if self.progress else None
        skipped = set(self.skipped()) if self.progress else set()
        return [
            _summary_chapter(
                ch,
                [
                    _summary_row(self.exercise(ex), states.get(ex), ex == current, ex in skipped)
                    for ex in ch.exercises
                ],
            )
            for ch in self.course.chapters
        ]


def diagnostics(settings: Settings) -> dict[str, Any]:
    """What this machine offers the grader, and where things live (``slamcourse doctor``)."""
    import platform

    import numpy

    from slamcourse import __version__
    from slamcourse.sandbox import probe_isolation

    report = probe_isolation()
    return {
        "slamcourse": __version__,
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "platform": platform.platform(),
        "isolation": report.level,
        "isolation_reason": report.reason,
        "course": str(course_root(settings.course)),
        "home": str(settings.home),
        "workspace": str(settings.workspace),
    }


def _tolerance(spec: ExerciseSpec) -> dict[str, Any] | None:
    if spec.kind not in ("number", "vector", "matrix", "expression"):
        return None
    opts = spec.options
    if getattr(opts, "exact", False):
        return {"rtol": 0.0, "atol": 0.0, "exact": True}
    tol = getattr(opts, "tolerance", None) or spec.tolerance
    return {
        "rtol": tol.rtol,
        "atol": tol.atol,
        "angle": bool(getattr(opts, "angle", False)),
        "exact": False,
    }


# ------------------------------------------------------------------------------ the summary


def _summary_row(
    spec: ExerciseSpec, state: ExerciseState | None, current: bool, skipped: bool
) -> dict[str, Any]:
    """One exercise's row of :meth:`Engine.summary`."""
    return {
        "id": spec.id,
        "title": spec.title,
        "kind": spec.kind,
        "status": state.status if state else "pending",
        "attempts": state.attempts if state else 0,
        "current": current,
        "skipped": skipped,  # still open; `next` passes over it
    }


def _summary_chapter(chapter: Chapter, rows: list[dict[str, Any]]) -> dict[str, Any]:
    """One chapter of :meth:`Engine.summary`."""
    return {
        "id": chapter.id,
        "title": chapter.title,
        "number": chapter.number,
        "exercises": rows,
        "solved": sum(r["status"] == "solved" for r in rows),
        "total": len(rows),
    }


class _SummaryCache:
    """:meth:`Engine.summary` kept from one call to the next.

    It holds its own copy of the exercise states, brought up to date from the store's changes
    since the revision it last saw (all of them when the store says its list is complete: the
    first call, a reset of everything, a write by another process), and the chapters last
    built. A call rebuilds only the chapters showing something that changed: an exercise's
    state, the ``next`` exercise (its old and new chapter), a skipped mark. A rebuilt chapter
    is a new dict (one already handed out never changes) and every caller gets copies, so
    callers on several threads neither see each other's changes nor can spoil the cache.
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._revision: int | None = None
        self._states: dict[str, ExerciseState] = {}
        self._chapters: list[dict[str, Any]] = []
        self._index: dict[str, int] = {}  # exercise id -> the index of its chapter
        self._current: str | None = None
        self._skipped: frozenset[str] = frozenset()

    def get(
        self, engine: Engine, current: str | None, skipped: frozenset[str]
    ) -> list[dict[str, Any]]:
        chapters = engine.course.chapters
        revision: int | None
        states: dict[str, ExerciseState]
        with self._lock:
            if engine.progress is None:
                revision, states, complete = None, {}, True
            else:
                revision, states, complete = engine.progress.changes_since(self._revision)
            if complete or len(self._chapters) != len(chapters):
                self._states = dict(states)
                self._index = {ex: i for i, ch in enumerate(chapters) for ex in ch.exercises}
                dirty = set(range(len(chapters)))
                built: list[dict[str, Any]] = [{} for _ in chapters]
            else:
                self._states.update(states)
                touched = set(states) | (self._skipped ^ skipped)
                if current != self._current:
                    touched.update(e for e in (self._current, current) if e is not None)
                dirty = {self._index[e] for e in touched if e in self._index}
                built = list(self._chapters)
            for i in dirty:
                chapter = chapters[i]
                rows = [
                    _summary_row(
                        engine.exercise(ex), self._states.get(ex), ex == current, ex in skipped
                    )
                    for ex in chapter.exercises
                ]
                built[i] = _summary_chapter(chapter, rows)
            self._chapters, self._revision = built, revision
            self._current, self._skipped = current, skipped
        return [{**ch, "exercises": [dict(r) for r in ch["exercises"]]} for ch in built]
