"""The property-test run: Hypothesis draws inputs in the trusted parent, a callee answers.

The callee is normally a sandboxed :class:`~slamcourse.sandbox.Worker`; the validator also uses
trusted in-process callees (misconception implementations from reference.py). Expected values are
computed here and never leave this process. Runs are deterministic: a fixed seed per exercise,
no example database, and the same explicit edge examples first.
"""

from __future__ import annotations

import contextlib
import copy
import hashlib
import threading
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

from slamcourse.course.model import Tolerance
from slamcourse.errors import GraderError
from slamcourse.grading.returns import compare, to_plain
from slamcourse.sandbox import CallResult, LearnerFrame
from slamcourse.sandbox.runner import StopReason

MAX_RECORDED = 20  # failing inputs kept for recognising misconceptions
_HYPOTHESIS = threading.RLock()


@contextlib.contextmanager
def hypothesis_run() -> Iterator[None]:
    """One Hypothesis run at a time, drawing the same inputs from the same seed in every
    process: Hypothesis (6.1xx) also draws numbers it finds in the source of the non-library
    modules a process happens to have imported ("local constants"), so that the same seed drew
    other inputs in a fresh script, in a validator and in a batch's grading processes. Those
    constants are switched off (and the cache of allowed constants emptied) for the run."""
    with _HYPOTHESIS:
        try:
            from hypothesis.internal.conjecture import providers as module
            from hypothesis.internal.constants_ast import Constants

            providers: Any = module
            empty = Constants(
                integers=type(providers.GLOBAL_CONSTANTS.integers)(),
                floats=type(providers.GLOBAL_CONSTANTS.floats)(key=providers.float_to_int),
                bytes=type(providers.GLOBAL_CONSTANTS.bytes)(),
                strings=type(providers.GLOBAL_CONSTANTS.strings)(),
            )
            get, cache = providers._get_local_constants, providers.CONSTANTS_CACHE.cache
        except (ImportError, AttributeError, TypeError):  # another Hypothesis: nothing to do
            yield
            return
        providers._get_local_constants = lambda: empty
        cache.clear()  # allowed constants, computed with the local ones
        try:
            yield
        finally:
            providers._get_local_constants = get
            cache.clear()


@dataclass(frozen=True)
class Failure:
    """One input on which the learner's function went wrong."""

    kwargs: dict[str, Any]
    expected: Any
    got: Any
    message: str
    kind: str  # "mismatch", "raised", "timeout", "crashed" or "protocol_error"
    frames: tuple[LearnerFrame, ...] = ()
    stdout: str = ""
    origin: str = ""  # the test set's case origin (``example``, ``boundary: …``, ``hidden 1``)


@dataclass
class Outcome:
    """What a run found: ``failure`` is the minimal (shrunk) failing input, if any."""

    examples: int = 0
    failure: Failure | None = None
    failures: list[Failure] = field(default_factory=list)
    seed: int = 0
    drawn: list[dict[str, Any]] = field(default_factory=list)  # inputs, in the order tried
    replayed: bool = False
    agreed: list[tuple[dict[str, Any], Any]] = field(default_factory=list)
    """``(input, reference value)`` of explicit examples the callee got right (collected with
    the failures): a misconception must be right there too to be named."""
    failure_case: Any = None  # the test set's case of ``failure`` (grading.testset.Case)
    output_cut: bool = False  # some of the callee's output was muted
    stopped: tuple[StopReason, int] | None = None
    """Why the callee's calls stopped (its output was cut, or a call left a process running:
    ``CallResult.stopped``), and how many had been made then."""
    hidden_failed: set[str] = field(default_factory=set)  # hidden runs with a failing input
    call_seconds: float = 0.0  # wall time the callee reported for its calls

    @property
    def passed(self) -> bool:
        return self.failure is None


class _Fatal(BaseException):
    """The callee is gone (timeout, crash, broken channel): stop at once, do not shrink."""

    def __init__(self, failure: Failure) -> None:
        super().__init__(failure.message)
        self.failure = failure


class TrustedCallee:
    """Calls a trusted, in-process function (reference code) as if it were a learner's."""

    def __init__(self, fn: Callable[..., Any]) -> None:
        self.fn = fn

    def call(self, args: Sequence[Any]) -> CallResult:
        try:
            return CallResult("ok", value=to_plain(self.fn(*copy.deepcopy(list(args)))))
        except Exception as exc:
            return CallResult("raised", error=f"{type(exc).__name__}: {exc}")


def exercise_seed(exercise_id: str) -> int:
    """The fixed Hypothesis seed of an exercise (recorded in every verdict)."""
    return int.from_bytes(hashlib.sha256(exercise_id.encode()).digest()[:4], "little")


def run(
    *,
    strategy: Any,
    examples: Sequence[dict[str, Any]],
    signature: Sequence[str],
    returns: Any,
    tolerance: Tolerance,
    reference: Callable[..., Any],
    call: Callable[[Sequence[Any]], CallResult],
    max_examples: int,
    seed: int,
    shrink: bool = True,
) -> Outcome:
    """Run the property test; returns the outcome (never raises for learner behaviour).

    ``shrink=False`` stops at the first failing input (the verdict's status is the same; the
    validator uses it for mutants, whose failing input nobody reads)."""
    from hypothesis import HealthCheck, Phase, Verbosity, example, given, settings
    from hypothesis import seed as fixed_seed

    outcome = Outcome(seed=seed)
    drawn: list[dict[str, Any]] = []
    outcome.drawn = drawn

    def record(failure: Failure) -> None:
        if len(outcome.failures) < MAX_RECORDED:
            outcome.failures.append(failure)
        outcome.failure = failure

    def body(kwargs: dict[str, Any]) -> None:
        outcome.examples += 1
        drawn.append(copy.deepcopy(kwargs))
        try:
            want = reference(**copy.deepcopy(kwargs))
        except Exception as exc:
            raise GraderError(
                f"the reference failed on {kwargs}: {type(exc).__name__}: {exc}; "
                "the exercise's 'arguments' must exclude undefined inputs"
            ) from exc
        result = call([kwargs[name] for name in signature])
        if result.status in ("timeout", "crashed", "protocol_error"):
            raise _Fatal(
                Failure(kwargs, want, None, result.error, result.status, stdout=result.stdout)
            )
        if result.status == "raised":
            record(
                Failure(kwargs, want, None, result.error, "raised", result.frames, result.stdout)
            )
            raise AssertionError(result.error)
        mismatch = compare(returns, result.value, want, tolerance)
        if mismatch is not None:
            record(
                Failure(
                    kwargs, want, result.value, mismatch.message, "mismatch", stdout=result.stdout
                )
            )
            raise AssertionError(mismatch.message)

    test = given(strategy)(body)  # type: ignore[no-untyped-call]
    for ex in reversed(examples):
        test = example(ex)(test)
    test = settings(
        max_examples=max_examples,
        database=None,
        deadline=None,
        derandomize=False,
        report_multiple_bugs=False,
        print_blob=False,
        verbosity=Verbosity.quiet,
        suppress_health_check=list(HealthCheck),
        phases=(Phase.explicit, Phase.generate, Phase.shrink)
        if shrink
        else (Phase.explicit, Phase.generate),
    )(test)
    test = fixed_seed(seed)(test)
    try:
        with hypothesis_run():  # one at a time (validate uses threads), same draws everywhere
            test()
    except _Fatal as fatal:
        outcome.failure = fatal.failure
    except AssertionError:
        if outcome.failure is None:  # pragma: no cover - an assertion of our own
            raise
    except GraderError:
        raise
    except Exception as exc:  # Hypothesis could not run (e.g. 'assume' rejects everything)
        raise GraderError(f"the property test could not run: {type(exc).__name__}: {exc}") from exc
    return outcome


def matching_misconception(
    outcome: Outcome,
    returns: Any,
    tolerance: Tolerance,
    candidates: Sequence[tuple[str, Callable[..., Any]]],
) -> str | None:
    """The id of the first misconception that explains the learner's function.

    It must reproduce the learner's results on every recorded failing input: return what the
    learner returned where the learner returned a wrong value (where the learner's code
    raised, the same idea may well have been written to return instead); and it must also be
    right wherever the learner was right on the fixed inputs (``outcome.agreed``: edge
    examples and boundary inputs). A solution that goes wrong in another way, or special-cases
    one input, is then not blamed on a misconception that merely shares one wrong value with
    it.
    """
    observed = [f for f in outcome.failures if f.kind == "mismatch"]
    if not observed:
        return None
    for mid, fn in candidates:
        try:
            if all(
                _reproduces(returns, f.got, fn(**copy.deepcopy(f.kwargs)), tolerance, f.expected)
                for f in observed
            ) and all(
                compare(returns, to_plain(fn(**copy.deepcopy(kwargs))), want, tolerance) is None
                for kwargs, want in outcome.agreed
            ):
                return mid
        except Exception:  # a misconception undefined on this input does not match
            continue
    return None


DIVERGED = 1e6
"""A result this many times farther from the reference's than the reference's own size has
diverged (an optimiser that blew up): two diverged results are the same mistake, whatever
digits the chaos left them with."""


def _reproduces(
    returns: Any, got: Any, theirs: Any, tolerance: Tolerance, expected: Any = None
) -> bool:
    """Whether a misconception's result ``theirs`` is what the learner returned (``got``):
    within the tolerance, or where a diverging mistake blows up (NaN, infinity, or both
    :data:`DIVERGED` times off the reference's value ``expected``), in the same places."""
    if compare(returns, got, theirs, tolerance) is None:
        return True
    import numpy as np

    try:
        a = np.asarray(to_plain(got), dtype=float)
        b = np.asarray(to_plain(theirs), dtype=float)
        want = np.asarray(to_plain(expected), dtype=float) if expected is not None else None
    except (TypeError, ValueError):
        return False
    if a.shape != b.shape:
        return False
    blown_a, blown_b = ~np.isfinite(a), ~np.isfinite(b)
    if want is not None and want.shape == a.shape and np.isfinite(want).all():
        limit = DIVERGED * np.maximum(1.0, np.abs(want))
        with np.errstate(invalid="ignore", over="ignore"):
            blown_a |= np.abs(a - want) > limit
            blown_b |= np.abs(b - want) > limit
    if not (blown_a == blown_b).all():
        return False
    keep = ~blown_a
    return bool(
        np.allclose(a[keep], b[keep], rtol=tolerance.rtol, atol=tolerance.atol, equal_nan=True)
    )
