"""Grading a class's submissions: each against the variants its learner was given.

The batch grader is a face of the engine: per submission it opens a fresh
:class:`~slamcourse.engine.Engine` in a temporary home (``record=False``, isolation required
unless relaxed) and renders what ``Engine.submit`` / ``Engine.submit_code`` return. Its only
rules are about submissions themselves (is it readable, made for this course, are its variant
seeds the learner's own) and the hidden checks of code exercises (below). A submission's problem
becomes that submission's error; the batch goes on.

A class is the unit of scale: what does not depend on the learner is paid once per batch.
Each code exercise's test set (:mod:`slamcourse.grading.testset`: its edge examples, the
boundary inputs of its argument types, the inputs a learner's own check draws, and
``hidden_runs`` × ``max_examples`` hidden inputs drawn with seeds derived from the grader's
secret and the exercise, :func:`~slamcourse.grading.testset.hidden_seed`), with the
reference's output on every input, is built once (in parallel, in the grading processes) and
shared by every submission; a submission's code exercises then run in workers forked from one
sandboxed zygote per submission, each a fresh process, graded in one pass over visible and
hidden inputs. Only the number of hidden runs that failed is reported, never their inputs.
"""

from __future__ import annotations

import contextlib
import gc
import math
import os
import re
import shutil
import tempfile
import time
import zipfile
from collections import Counter, deque
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, as_completed, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from slamcourse.batch.submission import (
    LEARNER_ID_PREFIX,
    Answer,
    Limits,
    Submission,
    SubmissionError,
    course_hash,
    learner_id,
    read,
)
from slamcourse.errors import SlamcourseError, UsageError
from slamcourse.grading.testset import SharedTests

if TYPE_CHECKING:
    from slamcourse.engine import Engine

RESULT_FORMAT = 1
TIMING_FIELDS = frozenset({"seconds", "learner_seconds"})
"""Keys whose values change from run to run; everything else is deterministic."""
MAX_ANSWER = 10_000
"""Characters of a text answer the grader reads (answers are numbers, vectors, formulas)."""
MAX_FEEDBACK = 4000
"""Characters of feedback kept per exercise (a flood of output stops here)."""


@dataclass(frozen=True)
class GradeOptions:
    """How a batch is graded (the same for every submission of the batch)."""

    course: Path | None = None
    require_isolation: bool = True
    secret: str = ""
    hidden_runs: int = 1
    limits: Limits = field(default_factory=Limits)


@dataclass(frozen=True)
class ExerciseGrade:
    """One exercise of one submission. ``status`` is a verdict status or ``missing``;
    ``hidden`` is ``{"runs": n, "failed": k}`` for code exercises whose hidden checks ran."""

    exercise: str
    title: str
    kind: str
    chapter: int
    variant: int
    status: str
    score: float
    feedback: str
    max_score: float = 1.0
    misconception: str | None = None
    attempts: int | None = None
    hidden: dict[str, int] | None = None
    command: str | None = None  # how the learner reproduces the visible check locally
    tests: list[dict[str, Any]] = field(default_factory=list)
    seconds: float = 0.0
    learner_seconds: float = 0.0  # of ``seconds``, the time inside the learner's own code

    @property
    def passed(self) -> bool:
        return self.status == "passed"

    def to_dict(self) -> dict[str, Any]:
        return {
            "exercise": self.exercise,
            "title": self.title,
            "kind": self.kind,
            "chapter": self.chapter,
            "variant": self.variant,
            "status": self.status,
            "score": self.score,
            "max_score": self.max_score,
            "feedback": self.feedback,
            "misconception": self.misconception,
            "attempts": self.attempts,
            "hidden": self.hidden,
            "command": self.command,
            "tests": self.tests,
            "seconds": self.seconds,
            "learner_seconds": self.learner_seconds,
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> ExerciseGrade:
        return cls(**{k: d[k] for k in cls.__dataclass_fields__ if k in d})


@dataclass(frozen=True)
class SubmissionGrade:
    """One submission: ``status`` ``graded`` (whatever the scores) or ``error`` (it could not be
    graded: ``error`` says why, ``exercises`` is empty)."""

    submission: str
    learner: str | None
    status: str
    exercises: tuple[ExerciseGrade, ...] = ()
    error: str | None = None
    warnings: tuple[str, ...] = ()
    seconds: float = 0.0
    fingerprint: str | None = None  # learner_id(learner seed): the same seed under two names

    @property
    def score(self) -> float:
        return round(sum(e.score for e in self.exercises), 6)

    @property
    def max_score(self) -> float:
        return sum(e.max_score for e in self.exercises)

    def to_dict(self) -> dict[str, Any]:
        return {
            "format": RESULT_FORMAT,
            "submission": self.submission,
            "learner": self.learner,
            "fingerprint": self.fingerprint,
            "status": self.status,
            "error": self.error,
            "warnings": list(self.warnings),
            "score": self.score,
            "max_score": self.max_score,
            "exercises": [e.to_dict() for e in self.exercises],
            "seconds": self.seconds,
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> SubmissionGrade:
        if d.get("format") != RESULT_FORMAT or "submission" not in d:
            raise UsageError(f"not a slamcourse grade result (format {d.get('format')!r})")
        return cls(
            submission=d["submission"],
            learner=d.get("learner"),
            status=d["status"],
            exercises=tuple(ExerciseGrade.from_dict(e) for e in d.get("exercises", [])),
            error=d.get("error"),
            warnings=tuple(d.get("warnings", [])),
            seconds=d.get("seconds", 0.0),
            fingerprint=d.get("fingerprint"),
        )


def without_timing(data: Any) -> Any:
    """``data`` with every timing field removed (what determinism compares)."""
    if isinstance(data, dict):
        return {k: without_timing(v) for k, v in data.items() if k not in TIMING_FIELDS}
    if isinstance(data, list):
        return [without_timing(v) for v in data]
    return data


# ------------------------------------------------------------------------------ selection


def shard(paths: Sequence[Path], spec: str | None) -> list[Path]:
    """Paths sorted; with ``K/N`` every N-th one starting at the (K-1)-th (K in 1..N)."""
    ordered = sorted(paths, key=lambda p: str(p))
    if not spec:
        return ordered
    m = re.fullmatch(r"(\d+)/(\d+)", spec.strip())
    if not m or not 1 <= int(m[1]) <= int(m[2]):
        raise UsageError(f"--shard {spec}: write K/N with 1 ≤ K ≤ N, e.g. --shard 2/4")
    k, n = int(m[1]), int(m[2])
    return ordered[k - 1 :: n]


def output_names(paths: Sequence[Path]) -> list[str]:
    """A safe, unique file-name stem per submission, from its path as the grader was given it
    (never from the submission's content)."""
    names: list[str] = []
    seen: dict[str, int] = {}
    for path in paths:
        stem = path.name[:-4] if path.name.lower().endswith(".zip") else path.name
        stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", stem).strip("._") or "submission"
        count = seen.get(stem, 0) + 1
        seen[stem] = count
        names.append(stem if count == 1 else f"{stem}-{count}")
    return names


# ------------------------------------------------------------------------------ hidden checks


_SHARED: dict[str, SharedTests] = {}
"""The batch's test sets in this process, by the file they were loaded from."""


def _shared_tests(path: str | None, options: GradeOptions) -> SharedTests:
    """The test sets a batch built (``path``: its pickle), else a fresh lazy set."""
    key = path or f"lazy:{options.secret}:{options.hidden_runs}"
    if key not in _SHARED:
        _SHARED[key] = (
            SharedTests.load(Path(path))
            if path
            else SharedTests(options.secret, options.hidden_runs)
        )
    return _SHARED[key]


def build_tests(course: Path | None, exercise_id: str, secret: str, runs: int, out: str) -> str:
    """One exercise's test set for a batch (run in a grading process): written to ``out`` for
    the other processes, which read it when they first need it, and kept by this one (returns
    ``out``)."""
    from slamcourse.course.locate import course_root

    spec = _course(course_root(course)).exercise(exercise_id)
    tests = SharedTests(secret, runs).get(spec)
    tests.encode_chunks(tuple(spec.options.signature))  # (sent with the set)
    SharedTests.write(tests, Path(out))
    return out


def _same_for_everyone(course: Any, exercise_id: str) -> bool:
    """A text exercise whose answer is the same for every learner: a reference, no drawn
    parameters (e.g. a figure of a whole data set, which can take seconds to compute)."""
    try:
        spec = course.exercise(exercise_id)
    except SlamcourseError:
        return False
    return spec.kind != "code" and spec.reference is not None and not spec.has_variants


def build_answers(course: Path | None, exercise_id: str) -> dict[Any, Any]:
    """The reference answer of a text exercise that is the same for every learner, and the
    values of its misconceptions, computed once for a batch (in one grading process, the answer
    first: a misconception derived from it, e.g. half of it, then costs nothing more) and
    adopted by every grading process with the test sets. Left to each process, every one that
    met a wrong answer would compute them again, and the answer too where its value came from
    another process (sphere2500's optimum and its misreading of Ω: 4.8 s together)."""
    from slamcourse.course import reference
    from slamcourse.course.locate import course_root
    from slamcourse.course.variants import variant
    from slamcourse.kinds import get_kind

    spec = _course(course_root(course)).exercise(exercise_id)
    calls = get_kind(spec.kind).reference_calls(spec, variant(spec, 0))
    return reference.kept_results(spec, calls)


# ------------------------------------------------------------------------------ one submission

_COURSE_HASHES: dict[Path, str] = {}
_COURSES: dict[Path, Any] = {}


def _course(root: Path) -> Any:
    """The course at ``root``, loaded once per grading process (content, no learner state)."""
    from slamcourse.course.loader import load_course

    if root not in _COURSES:
        _COURSES[root] = load_course(root)
    return _COURSES[root]


def _course_identity(root: Path) -> str:
    if root not in _COURSE_HASHES:
        _COURSE_HASHES[root] = course_hash(root)
    return _COURSE_HASHES[root]


def _check_claims(sub: Submission, engine: Engine, root: Path, name: str) -> list[str]:
    """Raise for a submission made for another course or with edited seeds; return warnings."""
    from slamcourse import __version__
    from slamcourse.progress import variant_seed_for

    m = sub.manifest
    ours = _course_identity(root)
    if m.course_hash != ours:
        raise SubmissionError(
            f"{name} was made for course version {m.course_version} ({m.course_hash[:19]}…), "
            f"not the course this grader has ({ours[:19]}…); grade it with that course "
            "(--course) or ask the learner to submit again"
        )
    if m.learner_name is None and m.learner_id != learner_id(m.learner_seed):
        raise SubmissionError(
            f"{name}: learner.id {m.learner_id} does not belong to learner.seed "
            f"(an unnamed learner's id is {LEARNER_ID_PREFIX}… derived from the seed); "
            "the manifest was edited"
        )
    if m.learner_name is not None and m.learner_id != m.learner_name:
        raise SubmissionError(f"{name}: learner.id must equal learner.name when a name is given")
    warnings: list[str] = []
    known = set(engine.course.exercise_ids)
    for answer in m.answers:
        if answer.exercise not in known:
            warnings.append(f"{answer.exercise} is not an exercise of this course; ignored")
            continue
        spec = engine.exercise(answer.exercise)
        own = variant_seed_for(m.learner_seed, spec.id) if spec.has_variants else 0
        if spec.kind == "code":
            own = 0
        if answer.variant != own:
            raise SubmissionError(
                f"{name}: {answer.exercise} claims variant {answer.variant}, but this learner "
                f"was given variant {own} (variant seeds derive from learner.seed and the "
                "exercise id); the manifest was edited"
            )
    if m.engine != __version__:
        warnings.append(f"made with slamcourse {m.engine}; graded with {__version__}")
    return warnings


def _own_variants(sub: Submission, engine: Engine) -> Submission:
    """Answers read from notebooks are on the learner's own variant: set it (from the seed)."""
    import dataclasses

    from slamcourse.progress import variant_seed_for

    if not any(a.own_variant for a in sub.manifest.answers):
        return sub
    known = set(engine.course.exercise_ids)
    answers = []
    for a in sub.manifest.answers:
        if a.own_variant and a.exercise in known:
            spec = engine.exercise(a.exercise)
            own = 0
            if spec.has_variants and spec.kind != "code":
                own = variant_seed_for(sub.manifest.learner_seed, spec.id)
            a = dataclasses.replace(a, variant=own)
        answers.append(a)
    manifest = dataclasses.replace(sub.manifest, answers=tuple(answers))
    return dataclasses.replace(sub, manifest=manifest)


def _command(answer: Answer) -> str:
    if answer.file is not None and answer.origin is not None:
        return f"run {answer.origin} again (%%slamcourse check {answer.exercise})"
    if answer.file is not None:
        return f"slamcourse check {answer.exercise} --file {answer.file}"
    text = (answer.text or "").replace("'", "'\\''")
    return f"slamcourse check {answer.exercise} --seed {answer.variant} --answer='{text[:200]}'"


def _grade_answer(
    engine: Engine,
    sub: Submission,
    answer: Answer,
    options: GradeOptions,
    shared: SharedTests,
    read_source: str | None = None,
) -> ExerciseGrade:
    """``read_source``: the code answer's source, when the caller has read it already
    (:func:`_source`); else it is read here, and a file that cannot be read is reported."""
    spec = engine.exercise(answer.exercise)
    chapter = engine.course.chapter_of(spec.id).number
    start = time.perf_counter()
    source = ""
    try:
        if answer.file is not None:
            if spec.kind != "code":
                raise SubmissionError(f"{spec.id} is a {spec.kind} exercise: answer it with text")
            source = (
                read_source if read_source is not None else _text(sub.source(answer), answer.file)
            )
            result = engine.submit_code(spec.id, source=source, tests=shared.get(spec))
        else:
            if spec.kind == "code":
                raise SubmissionError(f"{spec.id} is a code exercise: hand in a file")
            if len(answer.text or "") > MAX_ANSWER:
                raise SubmissionError(
                    f"{spec.id}: the answer is longer than {MAX_ANSWER} characters; not graded"
                )
            result = engine.submit(spec.id, answer.text or "", seed=answer.variant)
    except SlamcourseError as exc:  # the answer's own problem, or the grader's (said as such)
        ours = not isinstance(exc, SubmissionError)
        return ExerciseGrade(
            spec.id,
            spec.title,
            spec.kind,
            chapter,
            answer.variant,
            "error" if ours else "invalid",
            0.0,
            f"Not graded (a problem on the grader's side): {exc}" if ours else str(exc),
            attempts=answer.attempts,
            command=_command(answer),
            seconds=time.perf_counter() - start,
        )
    verdict = result.verdict
    status, score, feedback = verdict.status, verdict.score, _cap(verdict.feedback)
    hidden = None
    if spec.kind == "code" and options.hidden_runs > 0:
        runs = options.hidden_runs
        checks = f"{runs} hidden check{'s' if runs != 1 else ''}"
        details = verdict.details
        if verdict.passed:
            hidden = {"runs": runs, "failed": 0}
            feedback += f"\n\nThe {checks} (inputs your local check never drew) passed too."
        elif details.get("hidden"):
            failed = int(details.get("hidden_failed", 1)) or 1
            hidden = {"runs": runs, "failed": failed}
            feedback += (
                f"\n\n{failed} of {checks} failed: property tests on inputs your local "
                "check never drew. Your function is right on the inputs you saw but not "
                "on all the inputs the prompt allows; look for a case you did not handle."
            )
        elif status != "error":
            hidden = {"runs": 0, "failed": 0}
            feedback += f"\n\nThe {checks} run only once the visible check passes."
    return ExerciseGrade(
        spec.id,
        spec.title,
        spec.kind,
        chapter,
        answer.variant,
        status,
        score,
        feedback,
        misconception=verdict.misconception,
        attempts=answer.attempts,
        hidden=hidden,
        command=_command(answer),
        tests=result.tests,
        seconds=time.perf_counter() - start,
        learner_seconds=verdict.learner_seconds,
    )


def _source(sub: Submission, answer: Answer) -> str | None:
    """A code answer's source, or None where it cannot be read (reported when it is graded)
    or the answer is text."""
    if answer.file is None:
        return None
    try:
        return _text(sub.source(answer), answer.file)
    except SlamcourseError:
        return None


def _grading_order(
    answer: Answer, source: str | None, long: frozenset[str] = frozenset()
) -> tuple[int, bool]:
    """Text answers first (0), then code that does not use scipy (1), then code that does (2):
    its workers come from another zygote (:func:`~slamcourse.grading.pool.uses_scipy`); within
    each, the ``long`` exercises (that may run long) first: a task asked to stop
    (:func:`_to_stop`) then leaves the short ones, which share out well."""
    from slamcourse.grading.pool import uses_scipy

    if answer.file is None:
        return 0, answer.exercise not in long
    return (2 if source is not None and uses_scipy(source) else 1), answer.exercise not in long


def _text(data: bytes, name: str) -> str:
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise SubmissionError(
            f"{name}:{line}: byte {data[exc.start]:#04x} is not UTF-8 text; save the file as UTF-8"
        ) from None


def _cap(text: str) -> str:
    if len(text) <= MAX_FEEDBACK:
        return text
    return text[:MAX_FEEDBACK] + f"\n\n… ({len(text) - MAX_FEEDBACK} more characters cut)"


def _settle_heap() -> None:
    """Collect what the last submission left, then move everything still alive (the course,
    the batch's test sets: ~460,000 objects for the bundled course) out of the cyclic garbage
    collector's sight. Each full collection would otherwise walk all of it again, about once
    per thousand calls: 0.2–0.3 s of every submission. Refcounting still frees what dies."""
    gc.collect()
    gc.freeze()


def _limit_blas() -> Callable[[], None]:
    """Have this process compute with one BLAS thread (the references, the judges' numerics,
    the shared answers): BLAS libraries already loaded are limited (threadpoolctl), those
    loaded from now on start with one thread (their environment variables). Returns what
    undoes it. ``--jobs N`` runs N grading processes for N cores: a BLAS thread pool in each
    would oversubscribe them (its spinning threads cost more than they save: a test set's
    build took twice as long), and a result must not depend on ``--jobs`` (a sum split over
    threads can differ in its last bits with their number). The learners' code runs with one
    BLAS thread too (the sandbox's environment)."""
    from threadpoolctl import threadpool_limits

    from slamcourse.sandbox.isolation import ONE_BLAS_THREAD

    saved = {name: os.environ.get(name) for name in ONE_BLAS_THREAD}
    os.environ.update(dict.fromkeys(ONE_BLAS_THREAD, "1"))
    limiter = threadpool_limits(limits=1, user_api="blas")

    def undo() -> None:
        limiter.restore_original_limits()
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value

    return undo


@contextlib.contextmanager
def one_blas_thread() -> Iterator[None]:
    """One BLAS thread in this process while the context lasts (:func:`_limit_blas`)."""
    undo = _limit_blas()
    try:
        yield
    finally:
        undo()


_BOARD: tuple[Any, Any] | None = None
"""In a grading process of ``--jobs N``: (when each task slot's task started, whether it is
asked to stop), shared with the parent (:func:`_grade_all`)."""


def _grading_process(cpus: Sequence[int] = (), taken: Any = None, board: Any = None) -> None:
    """The first thing each grading process of ``--jobs N`` does: one BLAS thread, for good,
    and, given ``cpus`` (:func:`cpus_to_pin`), the next of them for itself alone (``taken``:
    a shared counter of the CPUs handed out). Its sandboxes and workers inherit the CPU.
    ``board``: the tasks' start times and stop flags it shares with the parent."""
    global _BOARD
    _BOARD = board
    _limit_blas()
    if cpus and taken is not None:
        with taken.get_lock():
            k = taken.value
            taken.value += 1
        with contextlib.suppress(OSError):
            os.sched_setaffinity(0, {cpus[k % len(cpus)]})


def cpus_to_pin(jobs: int) -> list[int]:
    """The CPUs the ``jobs`` grading processes are pinned to, one each: the first ``jobs`` this
    process may run on, when there are that many (else none: the system places them). A
    grading process is a tight pipeline (the grader sends a chunk of calls, the worker answers
    them while the grader judges, the zygote forks the next worker): kept on one CPU with its
    sandbox, its wake-ups do not wait for another CPU to pick them up, and two such pipelines
    on two CPUs kept both busy 1.92–1.95 of the time instead of 1.88–1.91 (a 24-submission
    class, alternated: 41.6–46.4 s instead of 44.0–47.5 s)."""
    try:
        allowed = sorted(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # (no affinity on this platform)
        return []
    return allowed[:jobs] if 1 < jobs <= len(allowed) else []


@dataclass(frozen=True)
class Part:
    """The exercises one task of a batch grades of a submission: those in ``exercises``
    (``inside``) or all the others. A submission graded in parts is checked whole by each
    (readable, made for this course, its own variants) and its parts merged (:func:`merged`)."""

    exercises: frozenset[str]
    inside: bool

    def __contains__(self, exercise: object) -> bool:
        return (exercise in self.exercises) == self.inside

    @property
    def single(self) -> bool:
        """One exercise: asked to stop (:func:`_to_stop`), it would have nothing to leave."""
        return self.inside and len(self.exercises) == 1


def grade_submission(
    path: Path,
    options: GradeOptions,
    shared_path: str | None = None,
    ahead: bool = False,
    part: Part | None = None,
) -> SubmissionGrade:
    """Grade one submission in a fresh engine and temporary home; never raises for anything
    the submission contains (its problems become ``status: error``). ``shared_path``: the
    batch's test sets (:func:`grade_all` builds them once); without it they are built here as
    needed and kept for the next submission graded in this process. ``ahead``: another
    submission may follow in this process: if it will need a sandbox zygote of its own (this
    process could not keep its last learner's:
    :func:`~slamcourse.grading.pool.zygote_needed_ahead`), it is started while this one is
    graded. ``part``: grade only those exercises (the result lists only them)."""
    return _grade(path, options, shared_path, ahead, part)[0]


def _grade(
    path: Path,
    options: GradeOptions,
    shared_path: str | None = None,
    ahead: bool = False,
    part: Part | None = None,
    stop: Callable[[], bool] | None = None,
) -> tuple[SubmissionGrade, frozenset[str]]:
    """:func:`grade_submission`, and the exercises it left ungraded: asked to ``stop`` (checked
    before each answer but the first), it grades no further answer, and its result lists
    neither those answers nor their exercises (another task grades them: :func:`_grade_all`)."""
    from slamcourse.course.locate import course_root
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    _settle_heap()
    start = time.perf_counter()
    name = path.name
    learner: str | None = None
    home = Path(tempfile.mkdtemp(prefix="slamcourse-grade-"))
    try:
        sub = read(path, options.limits)
        learner = sub.manifest.learner_id
        root = course_root(options.course)
        settings = Settings(
            home=home,
            workspace=home / "workspace",
            course=root,
            require_isolation=options.require_isolation,
            record=False,
        )
        code = any(
            a.file is not None and (part is None or a.exercise in part)
            for a in sub.manifest.answers
        )
        shared = _shared_tests(shared_path, options)
        with Engine.open(
            settings,
            with_progress=False,
            warm_sandbox=code,
            fork_workers=True,
            course=_course(root),
        ) as engine:
            if ahead:  # (after this submission took the zygote started for it)
                from slamcourse.grading.pool import start_zygote_ahead, zygote_needed_ahead

                for scipy in (False, True):
                    isolated = options.require_isolation
                    if zygote_needed_ahead(require_isolation=isolated, scipy=scipy):
                        start_zygote_ahead(require_isolation=isolated, scipy=scipy)
            sub = _own_variants(sub, engine)
            warnings = [*sub.notes, *_check_claims(sub, engine, root, name)]
            given = {
                a.exercise: a for a in sub.manifest.answers if part is None or a.exercise in part
            }
            graded: dict[str, ExerciseGrade] = {}
            # text answers first: the sandbox's zygotes start meanwhile; then the code that
            # does not use scipy, then the code that does: one switch between the two zygotes
            # (results keep the course's order)
            known = set(engine.course.exercise_ids)
            sources = {a.exercise: _source(sub, a) for a in given.values() if a.file is not None}
            long = _long_exercises(engine.course)
            order = sorted(
                (a for a in given.values() if a.exercise in known),
                key=lambda a: _grading_order(a, sources.get(a.exercise), long),
            )
            engine.expect_code(
                [(a.exercise, sources[a.exercise] or "") for a in order if a.file is not None]
            )
            left: frozenset[str] = frozenset()
            for n, answer in enumerate(order):
                if n and stop is not None and stop():
                    left = frozenset(a.exercise for a in order[n:])
                    break
                graded[answer.exercise] = _grade_answer(
                    engine, sub, answer, options, shared, sources.get(answer.exercise)
                )
            grades: list[ExerciseGrade] = []
            for ex in engine.course.exercise_ids:
                if (part is not None and ex not in part) or ex in left:
                    continue
                if ex in graded:
                    grades.append(graded[ex])
                else:
                    spec = engine.exercise(ex)
                    grades.append(
                        ExerciseGrade(
                            ex,
                            spec.title,
                            spec.kind,
                            engine.course.chapter_of(ex).number,
                            0,
                            "missing",
                            0.0,
                            "No answer was handed in for this exercise.",
                        )
                    )
        return SubmissionGrade(
            name,
            learner,
            "graded",
            tuple(grades),
            None,
            tuple(warnings),
            time.perf_counter() - start,
            fingerprint=learner_id(sub.manifest.learner_seed),
        ), left
    except SlamcourseError as exc:
        return SubmissionGrade(
            name, learner, "error", error=str(exc), seconds=time.perf_counter() - start
        ), frozenset()
    except Exception as exc:  # a grader bug must not stop the batch: said as such
        return SubmissionGrade(
            name,
            learner,
            "error",
            error=f"internal grader error ({type(exc).__name__}: {exc}); please report it",
            seconds=time.perf_counter() - start,
        ), frozenset()
    finally:
        shutil.rmtree(home, ignore_errors=True)


_Graded = tuple["SubmissionGrade", frozenset[str]]


def _grade_task(
    path: Path, options: GradeOptions, shared_path: str, part: Part | None, slot: int
) -> _Graded:
    """One task of a batch, in a grading process (:func:`_grade_all`): its start time written
    to its ``slot`` of the board, whose stop flag it heeds between answers."""
    if _BOARD is None:
        return _grade(path, options, shared_path, True, part)
    started, stop = _BOARD
    started[slot] = time.monotonic()
    return _grade(path, options, shared_path, True, part, lambda: bool(stop[slot]))


# ------------------------------------------------------------------------------ a batch


def duplicate_learners(grades: Sequence[SubmissionGrade]) -> list[str]:
    """Warnings for a learner id, or a learner seed (under different names), handed in more
    than once in a batch: two learners with one seed share every variant."""
    warnings = []
    for key in ("learner", "fingerprint"):
        groups: dict[str, list[SubmissionGrade]] = {}
        for g in grades:
            value = getattr(g, key)
            if value is not None:
                groups.setdefault(value, []).append(g)
        for who, subs in sorted(groups.items()):
            names = ", ".join(g.submission for g in subs)
            if key == "learner" and len(subs) > 1:
                warnings.append(f"learner {who} appears in {len(subs)} submissions: {names}")
            elif key == "fingerprint" and len({g.learner for g in subs}) > 1:
                warnings.append(f"one learner seed is claimed by {len(subs)} learners: {names}")
    return warnings


def preflight(options: GradeOptions) -> None:
    """Raise when no submission could be graded: the course is missing or its chapter index is
    broken (a usage or course error, not one error per submission)."""
    from slamcourse.course.loader import load_course
    from slamcourse.course.locate import course_root

    root = course_root(options.course)
    if not load_course(root).exercise_ids:
        raise UsageError(f"the course at {root} has no exercises to grade")
    _course_identity(root)


def grade_all(
    paths: Sequence[Path],
    options: GradeOptions,
    *,
    jobs: int = 1,
    pin: bool = True,
    on_done: Callable[[int, int, SubmissionGrade], None] | None = None,
) -> list[SubmissionGrade]:
    """Grade ``paths`` (results in the order given); ``jobs`` > 1 grades in worker processes,
    each pinned to a CPU of its own where there are enough (``pin``: :func:`cpus_to_pin`).

    With several processes, each code exercise's test set, and each text exercise's answer that
    is the same for every learner, is first built once, the exercises spread over the
    processes, and handed to all of them; one process builds each set (and computes each
    answer) when it first needs it and keeps it. A process with nothing left to do takes a
    share of what the task begun first has not graded yet (:func:`_to_stop`)."""
    if jobs < 1:
        raise UsageError("--jobs must be at least 1")
    preflight(options)
    with one_blas_thread():
        return _grade_all(paths, options, jobs, pin, on_done)


def _grade_all(
    paths: Sequence[Path],
    options: GradeOptions,
    jobs: int,
    pin: bool,
    on_done: Callable[[int, int, SubmissionGrade], None] | None,
) -> list[SubmissionGrade]:
    results: list[SubmissionGrade | None] = [None] * len(paths)
    total = len(paths)
    if jobs == 1 or total <= 1:
        for i, path in enumerate(paths):
            results[i] = grade_submission(path, options, ahead=i + 1 < total)
            if on_done:
                on_done(i + 1, total, results[i])  # type: ignore[arg-type]
        return [r for r in results if r is not None]
    import multiprocessing

    from slamcourse.course.loader import load_course
    from slamcourse.course.locate import course_root

    root = course_root(options.course)
    course = load_course(root)
    code_ids = [ex for ex in course.exercise_ids if _is_code(course, ex)]
    context = multiprocessing.get_context("forkserver")
    scratch = Path(tempfile.mkdtemp(prefix="slamcourse-batch-"))
    try:
        cpus = cpus_to_pin(jobs) if pin else []
        # each task out has a slot (as many as tasks out: processes and one waiting): when it
        # started (0: not yet) and whether it is asked to stop after its current answer
        started = context.Array("d", jobs + 1, lock=False)
        stop = context.Array("b", jobs + 1, lock=False)
        free = list(range(jobs, -1, -1))
        with ProcessPoolExecutor(
            max_workers=jobs,
            mp_context=context,
            initializer=_grading_process,
            initargs=(cpus, context.Value("i", 0), (started, stop)),
        ) as pool:
            shared = SharedTests(options.secret, options.hidden_runs)
            answers = [  # first: one of them may be the longest task (a whole data set)
                pool.submit(build_answers, root, ex)
                for ex in course.exercise_ids
                if _same_for_everyone(course, ex)
            ]
            ordered = sorted(code_ids, key=lambda ex: _build_cost(course, ex), reverse=True)
            builds = {
                pool.submit(
                    build_tests,
                    root,
                    ex,
                    options.secret,
                    options.hidden_runs,
                    str(scratch / f"set-{k}.pickle"),
                ): ex
                for k, ex in enumerate(ordered)
            }
            for built in as_completed(builds):
                with contextlib.suppress(Exception):  # left to each submission to report
                    shared.files[builds[built]] = built.result()
            for computed in as_completed(answers):
                with contextlib.suppress(Exception):  # (recomputed where needed, and reported)
                    shared.answers.update(computed.result())
            shared_path = scratch / "tests.pickle"
            shared.save(shared_path)
            long = _long_exercises(course)
            tasks = plan(paths, long, jobs, code_ids)
            queue = deque(enumerate(tasks))  # (key, (submission, part)) in the order taken
            running: dict[Future[_Graded], tuple[int, Part | None, int, int]] = {}
            parts: dict[int, dict[tuple[bool, int], SubmissionGrade]] = {}
            expected = Counter(i for i, _ in tasks)  # (a submission's parts: tasks, pieces)
            fresh = len(tasks)  # (the next key for a piece of what a stopped task left)
            done = 0
            while queue or running:
                # as many tasks handed out as processes, and one waiting: the order stays
                # the plan's, and what a task asked to stop leaves can still go ahead of it
                while queue and len(running) <= jobs:
                    k, (i, part) = queue.popleft()
                    slot = free.pop()
                    started[slot], stop[slot] = 0.0, 0
                    future = pool.submit(
                        _grade_task, paths[i], options, str(shared_path), part, slot
                    )
                    running[future] = (i, part, k, slot)
                slots = [slot for _, _, _, slot in running.values()]
                idle = jobs - len(running) - sum(stop[slot] for slot in slots)
                if not queue and idle > 0:  # a process with nothing to do: share a task's rest
                    out = [
                        (slot, started[slot])
                        for _, part, _, slot in running.values()
                        if not stop[slot] and (part is None or not part.single)
                    ]
                    for slot in _to_stop(out, idle, time.monotonic()):
                        stop[slot] = 1
                finished, _ = wait(running, timeout=1.0, return_when=FIRST_COMPLETED)
                for future in finished:
                    i, part, k, slot = running.pop(future)
                    free.append(slot)
                    try:
                        graded, left = future.result()
                    except Exception as exc:  # the worker process itself died
                        graded, left = (
                            SubmissionGrade(
                                paths[i].name,
                                None,
                                "error",
                                error=f"the grading process failed: {exc}",
                            ),
                            frozenset(),
                        )
                    if left:  # asked to stop: what it left, shared by every process, first
                        cut = _shares(left, code_ids, long, jobs)
                        queue.extendleft(reversed([(fresh + n, (i, p)) for n, p in enumerate(cut)]))
                        expected[i] += len(cut)
                        fresh += len(cut)
                    # (the part with every other exercise first: an error there is reported)
                    parts.setdefault(i, {})[(part is not None and part.inside, k)] = graded
                    if len(parts[i]) < expected[i]:
                        continue
                    got = parts.pop(i)
                    results[i] = merged([got[key] for key in sorted(got)], course.exercise_ids)
                    done += 1
                    if on_done:
                        on_done(done, total, results[i])  # type: ignore[arg-type]
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return [r for r in results if r is not None]


SPLIT_SHARE = 0.1
SPLIT_ROUNDS = 4
REST_PIECES = 3


def plan(
    paths: Sequence[Path], long: frozenset[str], jobs: int, others: Sequence[str] = ()
) -> list[tuple[int, Part | None]]:
    """The tasks of a batch graded by ``jobs`` processes, in the order the processes take
    them: submissions largest first (:func:`_largest_first`), except that the submissions
    graded last (a tenth of the batch, and at least ``SPLIT_ROUNDS`` per process) are graded
    in parts, and the parts with the ``long`` exercises (those that may run long:
    :meth:`~slamcourse.kinds.code.CodeOptions.may_run_long`) of all of them go first. The rest
    of each goes last, in up to ``REST_PIECES`` pieces: the course's ``others`` (its other code
    exercises, in its order) dealt out in turn to all but the last piece, which takes every
    exercise not in another part (the text answers too).

    How long a learner's code takes is unknown until it runs, and most of all on a whole data
    set: one learner's dense solve of INTEL took 10 s where the sparse ones took 0.1 s. Graded
    last, such a submission kept one process busy for 8 s after the other had finished (a
    tenth of a 50-submission class's time at ``--jobs 2``); graded first, the others' work
    fills that time. So can a learner whose code loops in every exercise: each of its calls
    runs to its time limit (5 s), four minutes in all, which pieces let both processes share.
    A part costs ~15 ms (the submission read again, an engine opened), so only the end of
    the batch is split."""
    order = _largest_first(paths)
    tasks: list[tuple[int, Part | None]] = [(i, None) for i in order]
    if not long or jobs < 2:
        return tasks
    count = min(len(order), max(SPLIT_ROUNDS * jobs, math.ceil(len(order) * SPLIT_SHARE)))
    split = order[len(order) - count :]
    rest = [ex for ex in others if ex not in long]
    groups = [frozenset(rest[k::REST_PIECES]) for k in range(REST_PIECES - 1)]
    groups = [g for g in groups if g]
    pieces = [Part(g, inside=True) for g in groups]
    pieces.append(Part(long.union(*groups), inside=False))
    first = Part(long, inside=True)
    return (
        [(i, first) for i in split]
        + tasks[: len(order) - count]
        + [(i, piece) for piece in pieces for i in split]
    )


STEAL_AFTER = 1.0
"""A task out this long (seconds) is asked to stop after its current answer when a process
has nothing left to do (:func:`_to_stop`); what it leaves is shared (:func:`_shares`)."""


def _to_stop(out: Sequence[tuple[int, float]], idle: int, now: float) -> list[int]:
    """Which of the tasks ``out`` (their slots, and when each started: 0, not yet) to ask to
    stop after their current answer, with ``idle`` processes that have nothing to do: the
    ``idle`` that started first, each at least ``STEAL_AFTER`` seconds ago (one started later
    is taken for nearly done: splitting what it leaves would cost more than it saves)."""
    begun = sorted((t, slot) for slot, t in out if 0 < t <= now - STEAL_AFTER)
    return [slot for _, slot in begun[:idle]]


def _shares(
    left: frozenset[str], code: Sequence[str], long: frozenset[str], count: int
) -> list[Part]:
    """What a task asked to stop left, in up to ``count`` pieces (one per process): its code
    exercises (``code``, in the course's order, the ``long`` ones first) dealt out in turn, and
    anything else with the first. A piece that takes long is cut again when a process has
    nothing to do, so that the batch ends on one exercise at most, never a submission."""
    ordered = sorted((ex for ex in code if ex in left), key=lambda ex: ex not in long)
    groups = [set(ordered[n::count]) for n in range(count)]
    groups[0] |= left.difference(ordered)
    return [Part(frozenset(g), inside=True) for g in groups if g]


def merged(parts: Sequence[SubmissionGrade], order: Sequence[str]) -> SubmissionGrade:
    """One submission's grade from the grades of its parts (:class:`Part`): the exercises in
    the course's ``order``, each part's warnings once; an error of any part (each part checks
    the whole submission) is the submission's."""
    if len(parts) == 1:
        return parts[0]
    seconds = sum(p.seconds for p in parts)
    for p in parts:
        if p.status != "graded":
            return SubmissionGrade(
                p.submission, p.learner, p.status, error=p.error, seconds=seconds
            )
    place = {ex: k for k, ex in enumerate(order)}
    exercises = sorted((e for p in parts for e in p.exercises), key=lambda e: place[e.exercise])
    warnings = tuple(dict.fromkeys(w for p in parts for w in p.warnings))
    first = parts[0]
    return SubmissionGrade(
        first.submission,
        first.learner,
        "graded",
        tuple(exercises),
        None,
        warnings,
        seconds,
        fingerprint=first.fingerprint,
    )


def _long_exercises(course: Any) -> frozenset[str]:
    """The course's code exercises that may run long (:func:`plan`)."""
    return frozenset(
        ex
        for ex in course.exercise_ids
        if _is_code(course, ex) and course.exercise(ex).options.may_run_long()
    )


def _largest_first(paths: Sequence[Path]) -> list[int]:
    """The order in which the processes take the submissions: most code files first, then the
    largest (more to grade), so that the batch does not end on one long submission graded while
    the other processes have nothing left to do (longest-processing-time-first scheduling).
    Results are still reported in the order given."""
    return sorted(range(len(paths)), key=lambda i: (*(-n for n in _weight(paths[i])), i))


def _weight(path: Path) -> tuple[int, int]:
    """(code files, bytes) of a submission, read from a zip's directory or a folder's tree; an
    unreadable one weighs nothing (it fails fast)."""
    try:
        if path.is_dir():
            files = [p for p in path.rglob("*") if p.is_file() and not p.is_symlink()]
            return sum(p.suffix == ".py" for p in files), sum(p.stat().st_size for p in files)
        if zipfile.is_zipfile(path):
            with zipfile.ZipFile(path) as archive:
                infos = archive.infolist()
            return sum(i.filename.endswith(".py") for i in infos), path.stat().st_size
        return 0, path.stat().st_size
    except (OSError, zipfile.BadZipFile):
        return 0, 0


def _build_cost(course: Any, exercise_id: str) -> tuple[int, int]:
    """A test set's expected cost, to build the costly ones first: exercises whose limits were
    raised (a whole data set), then those with more drawn inputs."""
    options = course.exercise(exercise_id).options
    return (1 if options.limits else 0, int(options.max_examples))


def _is_code(course: Any, exercise_id: str) -> bool:
    try:
        return bool(course.exercise(exercise_id).kind == "code")
    except SlamcourseError:
        return False


def summary_lines(grades: Sequence[SubmissionGrade]) -> list[str]:
    """One line per submission (``learner  submission  score/max`` or its error), then the
    batch's warnings."""
    lines = []
    for g in grades:
        score = f"{g.score:g}/{g.max_score:g}" if g.status == "graded" else f"error: {g.error}"
        lines.append(f"{g.learner or '?'}  {g.submission}  {score}")
    return lines + [f"warning: {w}" for w in duplicate_learners(grades)]


def bar_line(done: int, total: int, width: int = 30, label: str = "") -> str:
    """``[#####.....] 12/40 label``: one line of the progress bar the terminal face draws."""
    filled = width * done // total if total else width
    return f"[{'#' * filled}{'.' * (width - filled)}] {done}/{total} {label}".rstrip()
