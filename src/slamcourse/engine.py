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
from slamcourse.settings import Settings, activate_cache
from slamcourse.verdict import Verdict

if TYPE_CHECKING:
    from collections.abc import Callable

    from slamcourse.grading.pool import WorkerPool

NUDGE_AFTER = 2
"""Counted misses, with no hint taken, after which a result suggests a hint."""


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
        grader's engine, which serves one submission and checks many exercises). ``course``: the
        course already loaded from ``settings.course`` (a batch loads it once per process; its
        exercises are parsed once, not once per submission).
        """
        settings = settings or Settings.from_env()
        activate_cache(settings.cache)
        engine_pool = None
        if warm_sandbox:
            engine_pool = cls._new_pool(settings, keep_spare=False, fork=fork_workers)
            engine_pool.warm()
        try:
            if course is None:
                course = load_course(course_root(settings.course))
            progress = Progress.open(settings.home / "progress.sqlite3") if with_progress else None
        except BaseException:
            if engine_pool is not None:
                engine_pool.close()
            raise
        engine = cls(course, settings, progress)
        engine._pool = engine_pool
        engine._fork_workers = fork_workers
        return engine

    @staticmethod
    def _new_pool(settings: Settings, *, keep_spare: bool, fork: bool = False) -> WorkerPool:
        from slamcourse.grading.pool import WorkerPool

        return WorkerPool(
            require_isolation=settings.require_isolation, keep_spare=keep_spare, fork=fork
        )

    def start_workers(self) -> None:
        """For long-running faces: keep a sandbox worker ready for the next code check."""
        with self._pool_lock:
            if self._pool is None or not self._pool.keep_spare:
                old, self._pool = self._pool, self._new_pool(self.settings, keep_spare=True)
                if old is not None:
                    old.close()
            self._pool.warm()

    def close(self) -> None:
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

    def _take_worker(self, limits: Any = None) -> Any:
        """A fresh sandbox worker with ``limits`` (None: the defaults, which the pool's
        pre-started workers have)."""
        with self._pool_lock:
            if self._pool is None:
                self._pool = self._new_pool(
                    self.settings, keep_spare=False, fork=self._fork_workers
                )
            pool = self._pool
        return pool.take(limits)

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

    def _open_ids(self) -> list[str]:
        states = self._store().states()
        return [
            e
            for e in self.course.exercise_ids
            if states.get(e) is None or states[e].status == "pending"
        ]

    def next_exercise(self) -> str | None:
        """The pinned exercise if still open, else the first open one after it (wrapping)."""
        open_ids = self._open_ids()
        if not open_ids:
            return None
        current = self._store().current()
        if current in open_ids:
            return current
        order = self.course.exercise_ids
        if current in order:
            start = order.index(current)
            for ex in order[start + 1 :] + order[:start]:
                if ex in open_ids:
                    return ex
        return open_ids[0]

    def goto(self, exercise_id: str) -> None:
        self.exercise(exercise_id)  # unknown ids are a usage error
        self._store().set_current(exercise_id)

    def skip(self, exercise_id: str) -> str | None:
        """Move past ``exercise_id`` without solving it; returns the next open exercise."""
        order = self.course.exercise_ids
        open_ids = [e for e in self._open_ids() if e != exercise_id]
        start = order.index(exercise_id) if exercise_id in order else -1
        for ex in order[start + 1 :] + order[: start + 1]:
            if ex in open_ids:
                self._store().set_current(ex)
                return ex
        return None

    def reset(self, exercise_id: str | None = None) -> None:
        if exercise_id is not None:
            self.exercise(exercise_id)
        self._store().reset(exercise_id)

    def summary(self) -> list[dict[str, Any]]:
        """Per chapter: id, number, title, solved/total, and each exercise with its status."""
        states = self._store().states() if self.progress else {}
        current = self.next_exercise() if self.progress else None
        out = []
        for ch in self.course.chapters:
            rows = []
            for ex in ch.exercises:
                st = states.get(ex)
                spec = self.exercise(ex)
                rows.append(
                    {
                        "id": ex,
                        "title": spec.title,
                        "kind": spec.kind,
                        "status": st.status if st else "pending",
                        "attempts": st.attempts if st else 0,
                        "current": ex == current,
                    }
                )
            out.append(
                {
                    "id": ch.id,
                    "title": ch.title,
                    "number": ch.number,
                    "exercises": rows,
                    "solved": sum(r["status"] == "solved" for r in rows),
                    "total": len(rows),
                }
            )
        return out


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
