"""Test sets: the inputs a code exercise is graded on, with the reference's outputs, built once.

Nothing in a test set depends on the learner, so a batch builds each exercise's set once and
grades every submission against it (:class:`SharedTests`); a learner's own check builds the
visible part for itself. A test set is, in this order:

1. the exercise's explicit edge ``examples``;
2. the **boundary inputs** derived from the declared argument types
   (:mod:`slamcourse.grading.domains`: ±π and the floats next to it, whole numbers as ``int``,
   tuples and arrays where the prompt says sequence, the domain's extremes, g2o texts with CRLF
   or no final newline, …), applied to the examples and the first drawn inputs, and kept only
   where the exercise's reference is defined (it returns finite values without raising) and
   the exercise's ``valid`` function, if any, accepts them;
3. the **drawn** inputs: the course's shipped recording, else the learner's cache, else a
   Hypothesis draw with the exercise's fixed seed (the same sequence a passing run draws);
4. in grading mode, the **hidden** inputs: Hypothesis draws with seeds derived from the
   instructor's secret, which no learner's check ever meets (:func:`hidden_count` per run).

An input that occurs twice (same values *and* types: ``1`` and ``1.0``, a tuple and a list
differ) is kept once, at its first place, so a strategy that always draws the same data set
(``intel/whole-graph``) costs one call. Each case carries the reference's output, computed
here once: grading a submission is then one pass of calls and comparisons
(:func:`run_cases`).
"""

from __future__ import annotations

import copy
import functools
import hashlib
import json
import math
import pickle
import threading
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from slamcourse.course.model import ExerciseSpec, Tolerance
from slamcourse.errors import GraderError
from slamcourse.grading.properties import MAX_RECORDED, Failure, Outcome, exercise_seed
from slamcourse.grading.returns import accepted, compare, to_plain
from slamcourse.sandbox import CallResult

BOUNDARY_BASES = 12
"""Drawn inputs (after the examples) the boundary transforms may start from."""
CHUNK = 64
"""Inputs sent to the sandbox in one request."""
GROUP = 16
"""Results judged together as they stream in (:func:`~slamcourse.grading.returns.accepted`
clears a group of right values at once; the rest are judged one by one)."""
MAX_AGREED = 60
"""Inputs the learner got right that a misconception must get right too (examples and
boundaries first)."""
FATAL = ("timeout", "crashed", "protocol_error")


@dataclass(frozen=True)
class Case:
    """One input, the reference's output on it (plain data), and where it comes from:
    ``example``, ``boundary: <class>``, ``drawn`` or ``hidden <run>``."""

    kwargs: dict[str, Any]
    expected: Any
    origin: str

    @functools.cached_property
    def hidden(self) -> bool:
        return self.origin.startswith("hidden")

    @functools.cached_property
    def fixed(self) -> bool:
        """An explicit example or a boundary input (not drawn at random)."""
        return self.origin == "example" or self.origin.startswith("boundary")

    @functools.cached_property
    def expected_array(self) -> Any:
        """``expected`` as a float ndarray if it is a rectangular list of numbers (else None),
        converted once per batch process for every learner's comparison."""
        from slamcourse.grading.returns import numeric_array

        return numeric_array(self.expected)


@dataclass
class TestSet:
    """The cases of one exercise, visible ones first; ``recorded``: the drawn part came from a
    recording (no Hypothesis ran)."""

    exercise: str
    seed: int
    cases: list[Case]
    recorded: bool = False
    boundary_classes: tuple[str, ...] = ()

    def encoded_chunk(self, start: int, signature: tuple[str, ...], calls: list[Any]) -> bytes:
        """The sandbox request body of the chunk of cases from ``start`` (see
        :func:`~slamcourse.sandbox.protocol.encode_calls`), encoded once per process."""
        from slamcourse.sandbox.protocol import encode_calls

        cache: dict[tuple[int, tuple[str, ...]], bytes] = self.__dict__.setdefault("_bodies", {})
        key = (start, signature)
        if key not in cache:
            cache[key] = encode_calls(calls)
        return cache[key]

    def encode_chunks(self, signature: tuple[str, ...]) -> None:
        """Encode every chunk's request body now (a batch does it once, where it builds the
        set: the bodies travel with the set to every grading process, which would otherwise
        each encode them again)."""
        for start in range(0, len(self.cases), CHUNK):
            self.encoded_chunk(
                start, signature, _arguments(self.cases[start : start + CHUNK], signature)
            )

    @property
    def visible(self) -> list[Case]:
        return [c for c in self.cases if not c.hidden]

    @property
    def hidden_runs(self) -> int:
        return len({c.origin for c in self.cases if c.hidden})


def input_key(kwargs: dict[str, Any]) -> str:
    """A key equal for two inputs exactly when their values and types are equal."""
    from slamcourse.grading.replay import encode

    return json.dumps(encode(kwargs), sort_keys=True, allow_nan=True)


def draw(spec: ExerciseSpec, seed: int, *, examples: Sequence[dict[str, Any]] = ()) -> list[Any]:
    """The inputs a passing property run with ``seed`` draws (``examples`` first), without
    calling anything: the same sequence a learner's passing check meets."""
    from hypothesis import HealthCheck, Phase, Verbosity, example, given, settings
    from hypothesis import seed as fixed_seed

    from slamcourse.grading.properties import hypothesis_run
    from slamcourse.kinds import get_kind

    drawn: list[dict[str, Any]] = []

    def body(kwargs: dict[str, Any]) -> None:
        drawn.append(copy.deepcopy(kwargs))

    test = given(get_kind("code").strategy(spec))(body)  # type: ignore[attr-defined]
    for ex in reversed(examples):
        test = example(ex)(test)
    test = settings(
        max_examples=spec.options.max_examples,
        database=None,
        deadline=None,
        derandomize=False,
        verbosity=Verbosity.quiet,
        suppress_health_check=list(HealthCheck),
        phases=(Phase.explicit, Phase.generate),
    )(test)
    test = fixed_seed(seed)(test)
    try:
        with hypothesis_run():  # the same inputs from the same seed in every process
            test()
    except Exception as exc:  # e.g. 'assume' rejects everything
        raise GraderError(f"the property test could not run: {type(exc).__name__}: {exc}") from exc
    return drawn


HIDDEN_SHARE = 4
"""A hidden run draws ``max_examples // HIDDEN_SHARE`` inputs (at least :data:`HIDDEN_MIN`, at
most ``max_examples``): fresh inputs catch code fitted to the visible ones, while the visible
inputs, which the validator proves reject every shipped mutant, carry the exactness."""
HIDDEN_MIN = 10


def hidden_count(max_examples: int) -> int:
    """How many inputs one hidden run draws for an exercise with ``max_examples``."""
    return min(max_examples, max(HIDDEN_MIN, max_examples // HIDDEN_SHARE))


def hidden_spec(spec: ExerciseSpec) -> ExerciseSpec:
    """``spec`` with ``max_examples`` set to :func:`hidden_count` (what :func:`draw` reads)."""
    opts = spec.options
    count = hidden_count(opts.max_examples)
    if count == opts.max_examples:
        return spec
    return replace(spec, options=replace(opts, max_examples=count))


def _finite(value: Any) -> bool:
    value = to_plain(value)
    if isinstance(value, list):
        return all(_finite(v) for v in value)
    if isinstance(value, float):
        return math.isfinite(value)
    return True


def _drawn_inputs(spec: ExerciseSpec, seed: int, use_recording: bool) -> tuple[list[Any], bool]:
    """The visible drawn inputs and whether they came from a recording."""
    from slamcourse.grading import replay

    opts = spec.options
    cache_key = None
    if use_recording:
        shipped = replay.load_shipped(spec, seed)
        if shipped is not None:
            return shipped, True
        cache_key = replay.recording_key(spec, seed, opts.max_examples)
        cached = replay.load(cache_key)
        if cached:
            return cached, True
    inputs = draw(spec, seed, examples=opts.examples)
    if cache_key is not None:
        replay.save(cache_key, inputs)
    return inputs, False


def build(
    spec: ExerciseSpec,
    *,
    hidden_seeds: Sequence[int] = (),
    use_recording: bool = True,
) -> TestSet:
    """The test set of a code exercise (see the module docstring)."""
    from slamcourse.course import reference

    opts = spec.options
    ref = reference.function(spec, spec.reference or "", spec.reference_line)
    valid = (
        reference.function(spec, opts.valid, opts.valid_line)
        if getattr(opts, "valid", None)
        else None
    )
    assumed = None
    if getattr(opts, "assume", None) and getattr(opts, "arguments", None):
        from slamcourse.grading.domains import assumptions

        assumed = assumptions(opts.arguments, opts.assume)
    seed = exercise_seed(spec.id)
    drawn, recorded = _drawn_inputs(spec, seed, use_recording)
    cases: list[Case] = []
    seen: set[str] = set()

    outputs: dict[str, tuple[Any, Exception | None]] = {}  # an input's key: (output, error)

    def output(kwargs: dict[str, Any], key: str) -> tuple[Any, Exception | None]:
        """The reference's output on ``kwargs`` (plain data), or the exception it raised:
        computed once per input, whether it is a base, a derived input or a case."""
        if key not in outputs:
            try:
                outputs[key] = (to_plain(ref(**copy.deepcopy(kwargs))), None)
            except Exception as exc:
                outputs[key] = (None, exc)
        return outputs[key]

    judged: dict[str, bool] = {}  # a derived input's key: in the domain

    def admissible(kwargs: dict[str, Any]) -> bool:
        """Whether a derived input lies in the exercise's domain (``valid``, ``assume``, the
        reference defined and finite there)."""
        key = input_key(kwargs)
        if key not in judged:
            try:
                inside = (valid is None or bool(valid(**copy.deepcopy(kwargs)))) and (
                    assumed is None or bool(assumed(**copy.deepcopy(kwargs)))
                )
            except Exception:  # outside the domain the prompt states
                inside = False
            if inside:  # (the reference is asked only inside the domain)
                want, error = output(kwargs, key)
                inside = error is None and _finite(want)
            judged[key] = inside
        return judged[key]

    def cost(base: dict[str, Any]) -> int:
        """How costly a base is for every learner: its size and its output's (``n`` samples)."""
        from slamcourse.grading.domains import input_size

        return input_size(base) + input_size(output(base, input_key(base))[0])

    def add(kwargs: dict[str, Any], origin: str, *, derived: bool = False) -> bool:
        """Add one input; True if the test set holds it afterwards (added now or before)."""
        key = input_key(kwargs)
        if key in seen:
            return True
        if derived and not admissible(kwargs):
            return False
        want, error = output(kwargs, key)
        if error is not None:
            raise GraderError(
                f"the reference failed on {kwargs}: {type(error).__name__}: {error}; "
                "the exercise's 'arguments' must exclude undefined inputs"
            ) from error
        seen.add(key)
        cases.append(Case(kwargs, want, origin))
        return True

    for ex in opts.examples:
        add(copy.deepcopy(ex), "example")
    classes: tuple[str, ...] = ()
    types = getattr(opts, "types", ())
    if types:
        from slamcourse.grading.domains import boundary_inputs

        bases = [*opts.examples, *drawn[: BOUNDARY_BASES + len(opts.examples)]]
        found = set()
        for derived in boundary_inputs(types, bases, admissible=admissible, size=cost):
            if add(derived.kwargs, f"boundary: {derived.label}", derived=True):
                found.add(derived.label)  # (an input already there reaches the class too)
        classes = tuple(sorted(found))
    for kwargs in drawn:
        add(kwargs, "drawn")
    if hidden_seeds:
        sized = hidden_spec(spec)
        for run, hidden in enumerate(hidden_seeds):
            for kwargs in draw(sized, hidden):
                add(kwargs, f"hidden {run + 1}")
    return TestSet(spec.id, seed, cases, recorded, classes)


# ------------------------------------------------------------------------------ grading


CallMany = Callable[[Sequence[Sequence[Any]]], list[CallResult]]


class Calls(list[list[Any]]):
    """The argument lists of one chunk; ``encoded``: the same, already encoded for the
    sandbox (a :class:`~slamcourse.sandbox.Worker` sends it as is); ``enough(i, result)``:
    called by the worker with each result as it arrives, True to stop there. Other callees
    may ignore both."""

    encoded: bytes | None = None
    enough: Callable[[int, CallResult], bool] | None = None


def _arguments(chunk: Sequence[Case], signature: Sequence[str]) -> list[list[Any]]:
    """Each case's argument list, in the signature's order (what one request sends)."""
    return [[case.kwargs[name] for name in signature] for case in chunk]


def run_cases(
    tests: TestSet,
    call_many: CallMany,
    *,
    signature: Sequence[str],
    returns: Any,
    tolerance: Tolerance,
    mutable: Iterable[str] = (),
    cases: Sequence[Case] | None = None,
    max_failures: int = MAX_RECORDED,
    stop_worker: bool = True,
    judge: Any = None,
) -> tuple[Outcome, list[Case | None]]:
    """Call the learner's function on every case (``cases``: a subset) and compare.

    Returns the outcome (``failure``: the first failing case in order, unshrunk; ``failures``:
    up to :data:`~slamcourse.grading.properties.MAX_RECORDED` of them; ``agreed``: fixed cases
    the learner got right) and, parallel to ``outcome.failures``, the case of each failure.
    Stops at the first fatal result (timeout, crash, broken channel), after output was cut
    (the function flooded its output), after a call that left a process it started running
    (both: ``outcome.stopped``), and after ``max_failures`` failures
    (the validator needs only the first: whether a file passes); with ``stop_worker``, a
    worker is stopped mid-chunk once the last failure wanted arrives.
    An argument the function changed in place (unless its name is in ``mutable``) is a
    failure of its own kind, ``mutated``. ``judge``: the exercise's judge
    (:data:`~slamcourse.grading.returns.Judge`), which decides instead of the tolerance.
    """
    todo = list(tests.cases if cases is None else cases)
    outcome = Outcome(seed=tests.seed, replayed=tests.recorded)
    failed_cases: list[Case | None] = []
    allowed = set(mutable)
    whole = cases is None
    for start in range(0, len(todo), CHUNK):
        chunk = todo[start : start + CHUNK]
        calls = Calls(_arguments(chunk, signature))
        if whole:  # the same chunks for every learner: encoded for the sandbox once
            calls.encoded = tests.encoded_chunk(start, tuple(signature), calls)
        judged: list[Failure | None] = []  # the verdicts of the first results, in order
        received: list[CallResult] = []
        stop_at: list[int] = []  # where the last failure wanted is (the worker stops there)
        seen = [len(outcome.failures)]  # failures so far, this chunk's judged ones included

        def judge_upto(
            results: Sequence[CallResult],
            chunk: list[Case] = chunk,
            judged: list[Failure | None] = judged,
            stop_at: list[int] = stop_at,
            seen: list[int] = seen,
        ) -> None:
            """Judge ``results`` from the first not judged yet, as one group."""
            lo = len(judged)
            judged.extend(
                _judge_group(
                    chunk[lo : len(results)], results[lo:], signature, returns, tolerance,
                    allowed, judge,
                )
            )  # fmt: skip
            for k in range(lo, len(judged)):
                if judged[k] is not None and not stop_at:
                    seen[0] += 1
                    if seen[0] >= max_failures:
                        stop_at.append(k)

        def enough(
            index: int,
            result: CallResult,
            received: list[CallResult] = received,
            judged: list[Failure | None] = judged,
            stop_at: list[int] = stop_at,
        ) -> bool:
            """Judged in groups as the results stream in (a call that did not return a value
            untouched at once: it fails, or may): once the last failure wanted is among them,
            the worker is stopped (not left computing inputs nobody will read)."""
            received.append(result)
            if len(received) - len(judged) >= GROUP or result.status != "ok" or result.mutated:
                judge_upto(received)
            return bool(stop_at)

        if stop_worker:  # (not when the caller still needs the worker, e.g. to shrink)
            calls.enough = enough
        results = call_many(calls)
        if len(judged) < len(results):
            judge_upto(results)
        if stop_worker and stop_at:  # read as if the worker had stopped right there
            results = results[: stop_at[0] + 1]
        stop = False
        for index, (case, result) in enumerate(zip(chunk, results, strict=False)):
            outcome.examples += 1
            outcome.call_seconds += result.seconds or 0.0
            failure = judged[index]
            if result.output_cut:
                outcome.output_cut = True
            if failure is None:
                if case.fixed and len(outcome.agreed) < MAX_AGREED:
                    outcome.agreed.append((case.kwargs, case.expected))
            else:
                if outcome.failure is None:
                    outcome.failure = failure
                    outcome.failure_case = case
                if len(outcome.failures) < MAX_RECORDED:
                    outcome.failures.append(failure)
                    failed_cases.append(case)
                if case.hidden:
                    outcome.hidden_failed.add(case.origin)
            if result.status in FATAL:
                stop = True
                break
            if result.stopped is not None:
                outcome.stopped = (result.stopped, outcome.examples)
                stop = True
                break
        if stop or len(results) < len(chunk):
            break
        if len(outcome.failures) >= max_failures:
            break
    return outcome, failed_cases


def _judge_group(
    cases: Sequence[Case],
    results: Sequence[CallResult],
    signature: Sequence[str],
    returns: Any,
    tolerance: Tolerance,
    allowed: set[str],
    judge: Any = None,
) -> list[Failure | None]:
    """:func:`_judge` of each result, the values :func:`accepted` clears at once (those of a
    finished call that changed no argument) without comparing them one by one."""
    clear = [False] * len(results)
    if judge is None:
        ok = [i for i, r in enumerate(results) if r.status == "ok" and not r.mutated]
        if ok:
            arrays = [cases[i].expected_array for i in ok] if returns == "array" else None
            shown = accepted(
                returns,
                [results[i].value for i in ok],
                [cases[i].expected for i in ok],
                tolerance,
                arrays,
                [results[i].array for i in ok] if returns == "array" else None,
            )
            for i, yes in zip(ok, shown, strict=True):
                clear[i] = yes
    return [
        None if cleared else _judge(case, result, signature, returns, tolerance, allowed, judge)
        for case, result, cleared in zip(cases, results, clear, strict=False)
    ]


def _judge(
    case: Case,
    result: CallResult,
    signature: Sequence[str],
    returns: Any,
    tolerance: Tolerance,
    allowed: set[str],
    judge: Any = None,
) -> Failure | None:
    kwargs, want = case.kwargs, case.expected
    if result.status in FATAL:
        return Failure(
            kwargs,
            want,
            None,
            result.error,
            result.status,
            stdout=result.stdout,
            origin=case.origin,
        )
    if result.status == "raised":
        return Failure(
            kwargs,
            want,
            None,
            result.error,
            "raised",
            result.frames,
            result.stdout,
            origin=case.origin,
        )
    mismatch = compare(
        returns,
        result.value,
        want,
        tolerance,
        plain=True,
        judge=judge,
        kwargs=kwargs,
        want_array=case.expected_array if returns == "array" else None,
        got_array=result.array if returns == "array" else None,
    )
    if mismatch is not None:
        return Failure(
            kwargs,
            want,
            result.value,
            mismatch.message,
            "mismatch",
            stdout=result.stdout,
            origin=case.origin,
        )
    changed = [signature[i] for i in getattr(result, "mutated", ()) if 0 <= i < len(signature)]
    changed = [name for name in changed if name not in allowed]
    if changed:
        names = ", ".join(f"`{n}`" for n in changed)
        return Failure(
            kwargs,
            want,
            result.value,
            f"the function changed its argument{'s' if len(changed) > 1 else ''} {names} in "
            "place; the prompt asks for a new value: work on a copy "
            "(e.g. `list(x)` or `np.array(x, dtype=float)`) and leave the arguments as given",
            "mutated",
            stdout=result.stdout,
            origin=case.origin,
        )
    return None


# ------------------------------------------------------------------------------ a batch


def hidden_seed(secret: str, exercise_id: str, run: int) -> int:
    """The Hypothesis seed of hidden run ``run`` of an exercise in a batch: 32 bits of
    HMAC-SHA256(secret, id, run), never the exercise's public seed. Without the secret, no
    learner can predict it."""
    import hmac

    message = f"{exercise_id}\0{run}".encode()
    digest = hmac.new(secret.encode(), message, hashlib.sha256).digest()
    seed = int.from_bytes(digest[:4], "little")
    return seed if seed != exercise_seed(exercise_id) else seed ^ 1


_WRITTEN: dict[str, TestSet] = {}
"""The test sets this process wrote (:meth:`SharedTests.write`), by file: read from here."""


@dataclass
class SharedTests:
    """The test sets of one batch: each exercise's built once (inputs, hidden inputs from the
    instructor's ``secret``, reference outputs) and used for every submission. Thread-safe;
    :meth:`save` / :meth:`load` hand them to grading processes (a pickle of plain data, written
    and read only by the grader itself), with ``answers``: reference results that are the same
    for every learner (:func:`~slamcourse.course.reference.kept_results`), which a grading
    process adopts on :meth:`load`. ``files``: sets that a grading process built and wrote
    (:meth:`write`), read when first needed by every other process; the one that built a set
    keeps it (its parent and the other processes never unpickle what they do not use)."""

    secret: str = ""
    runs: int = 1
    sets: dict[str, TestSet] = field(default_factory=dict)
    answers: dict[Any, Any] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def get(self, spec: ExerciseSpec) -> TestSet:
        with self._lock:
            found = self.sets.get(spec.id)
            if found is None and spec.id in self.files:
                found = self._read(self.files[spec.id])
            if found is None:
                seeds = [hidden_seed(self.secret, spec.id, r) for r in range(self.runs)]
                found = build(spec, hidden_seeds=seeds)
            self.sets[spec.id] = found
            return found

    @staticmethod
    def _read(path: str) -> TestSet | None:
        if path in _WRITTEN:
            return _WRITTEN[path]
        try:
            found = pickle.loads(Path(path).read_bytes())  # our own file, never a learner's
        except Exception:  # (e.g. a disk error): built again, the same set
            return None
        return found if isinstance(found, TestSet) else None

    @staticmethod
    def write(tests: TestSet, path: Path) -> None:
        """Write one set for the other grading processes; this one keeps it."""
        path.write_bytes(pickle.dumps(tests))
        _WRITTEN[str(path)] = tests

    def save(self, path: Path) -> None:
        data = (self.secret, self.runs, self.sets, self.answers, self.files)
        path.write_bytes(pickle.dumps(data))

    @classmethod
    def load(cls, path: Path) -> SharedTests:
        from slamcourse.course import reference

        # our own file, never a learner's
        secret, runs, sets, answers, files = pickle.loads(path.read_bytes())
        reference.adopt_results(answers)
        return cls(secret, runs, sets, answers, files)
