"""The engine: what a learner can do, independent of the interface (terminal now, browser later).

It ties the course (what to ask), the kinds (how to grade) and the progress store (what happened)
together. It never prints; the CLI and, later, the web server present its results.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from slamcourse.course import templates, variants
from slamcourse.course.loader import Course, chapter_segments, load_course
from slamcourse.course.locate import course_root
from slamcourse.course.model import ExerciseSpec, Variant
from slamcourse.errors import UsageError
from slamcourse.kinds import get_kind
from slamcourse.progress import ExerciseState, Progress
from slamcourse.verdict import Verdict

if TYPE_CHECKING:
    from slamcourse.grading.pool import WorkerPool


@dataclass(frozen=True)
class Prompt:
    """Everything needed to pose one exercise."""

    exercise_id: str
    title: str
    kind: str
    chapter_title: str
    position: tuple[int, int]  # (index of the exercise in its chapter, from 1; count)
    variant: Variant
    markdown: str  # the rendered prompt followed by the kind's extra block
    how_to_answer: str


@dataclass(frozen=True)
class Hint:
    number: int
    total: int
    text: str | None  # None when there are no more hints


class Engine:
    """A course plus (optionally) a learner's progress."""

    def __init__(
        self, course: Course, progress: Progress | None = None, *, pool: WorkerPool | None = None
    ) -> None:
        self.course = course
        self.progress = progress
        self.pool = pool  # a long-running engine keeps a sandbox worker ready for code checks

    @classmethod
    def open(
        cls,
        course_path: str | Path | None = None,
        *,
        with_progress: bool = True,
        progress_path: Path | None = None,
    ) -> Engine:
        course = load_course(course_root(course_path))
        progress = Progress.open(progress_path) if with_progress else None
        return cls(course, progress)

    def close(self) -> None:
        if self.progress is not None:
            self.progress.close()
        if self.pool is not None:
            self.pool.close()

    def __enter__(self) -> Engine:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ---------------------------------------------------------------- variants
    def exercise(self, exercise_id: str) -> ExerciseSpec:
        return self.course.exercise(exercise_id)

    def variant(
        self, exercise_id: str, *, canonical: bool = False, seed: int | None = None
    ) -> Variant:
        """The learner's own variant, or the canonical one (0), or variant ``seed``."""
        spec = self.exercise(exercise_id)
        if seed is not None and seed < 0:
            raise UsageError("--seed takes a whole number ≥ 0 (0 is the canonical variant)")
        if canonical:
            chosen = 0
        elif seed is not None:
            chosen = seed
        elif self.progress is not None and spec.has_variants:
            chosen = self.progress.variant_seed(exercise_id)
        else:
            chosen = 0
        return variants.variant(spec, chosen)

    # ---------------------------------------------------------------- posing and grading
    def prompt(self, exercise_id: str, variant: Variant) -> Prompt:
        spec = self.exercise(exercise_id)
        kind = get_kind(spec.kind)
        text = templates.render(spec, spec.prompt, dict(variant.params))
        extra = kind.extra(spec, variant)
        chapter = self.course.chapter_of(exercise_id)
        index = chapter.exercises.index(exercise_id) + 1
        return Prompt(
            exercise_id,
            spec.title,
            spec.kind,
            chapter.title,
            (index, len(chapter.exercises)),
            variant,
            text + ("\n\n" + extra if extra else ""),
            kind.how_to_answer(spec, variant),
        )

    def context(self, exercise_id: str) -> str:
        """The chapter prose that leads up to this exercise (Markdown)."""
        chapter = self.course.chapter_of(exercise_id)
        for ex_id, prose in chapter_segments(chapter):
            if ex_id == exercise_id:
                return prose.strip()
        return ""

    def check(
        self, exercise_id: str, answer: str, variant: Variant, *, record: bool = True
    ) -> Verdict:
        """Grade ``answer``; record the attempt in the learner's progress when there is one."""
        spec = self.exercise(exercise_id)
        if spec.kind == "code":
            raise UsageError(
                f"{exercise_id} is a code exercise: grade a file with "
                f"`slamcourse check {exercise_id} --file PATH`"
            )
        verdict = get_kind(spec.kind).check(spec, variant, answer)
        if record and self.progress is not None:
            self.progress.record_attempt(exercise_id, variant.seed, answer, verdict)
        return verdict

    def check_code(
        self,
        exercise_id: str,
        path: Path,
        *,
        require_isolation: bool = False,
        record: bool = True,
        worker: Any = None,
    ) -> Verdict:
        """Grade the learner's file ``path`` for a code exercise (sandboxed)."""
        import hashlib

        from slamcourse.kinds.code import read_source

        spec = self.exercise(exercise_id)
        if spec.kind != "code":
            raise UsageError(f"{exercise_id} is a {spec.kind} exercise: answer it with --answer")
        source = read_source(path)
        if worker is None and self.pool is not None:
            worker = self.pool.take()
        verdict: Verdict = get_kind("code").check_source(  # type: ignore[attr-defined]
            spec, source, path.name, require_isolation=require_isolation, worker=worker
        )
        if record and self.progress is not None:
            digest = hashlib.sha256(source.encode("utf-8", "replace")).hexdigest()[:16]
            self.progress.record_attempt(exercise_id, 0, f"{path} sha256:{digest}", verdict)
        return verdict

    def code_file(self, exercise_id: str, *, create: bool = True) -> tuple[Path, bool]:
        """The learner's file of a code exercise, written from the starter when missing."""
        from slamcourse.workspace import ensure_starter, exercise_file

        spec = self.exercise(exercise_id)
        if spec.kind != "code":
            raise UsageError(f"{exercise_id} is not a code exercise")
        if create:
            return ensure_starter(spec)
        return exercise_file(spec), False

    def explanation(self, exercise_id: str, variant: Variant) -> str:
        spec = self.exercise(exercise_id)
        answer: Any = get_kind(spec.kind).expected(spec, variant)
        return templates.render(spec, spec.explanation, {**variant.params, "answer": answer})

    # ---------------------------------------------------------------- progress
    def _store(self) -> Progress:
        if self.progress is None:
            raise UsageError("this command needs learner progress")
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

    def hint(self, exercise_id: str, variant: Variant) -> Hint:
        spec = self.exercise(exercise_id)
        store = self._store()
        shown = store.state(exercise_id).hints_shown
        total = len(spec.hints)
        if shown >= total:
            return Hint(total, total, None)
        number = store.reveal_hint(exercise_id)
        text = templates.render(spec, spec.hints[number - 1], dict(variant.params))
        return Hint(number, total, text)

    def hints_shown(self, exercise_id: str, variant: Variant) -> list[str]:
        spec = self.exercise(exercise_id)
        shown = self._store().state(exercise_id).hints_shown
        return [templates.render(spec, h, dict(variant.params)) for h in spec.hints[:shown]]

    def give_up(self, exercise_id: str) -> ExerciseState:
        self.exercise(exercise_id)
        return self._store().give_up(exercise_id)

    def reset(self, exercise_id: str | None = None) -> None:
        if exercise_id is not None:
            self.exercise(exercise_id)
        self._store().reset(exercise_id)

    def summary(self) -> list[dict[str, Any]]:
        """Per chapter: id, title, and each exercise with its title-free status."""
        states = self._store().states() if self.progress else {}
        current = self.next_exercise() if self.progress else None
        out = []
        for ch in self.course.chapters:
            rows = []
            for ex in ch.exercises:
                st = states.get(ex)
                rows.append(
                    {
                        "id": ex,
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
