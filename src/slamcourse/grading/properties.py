"""The property-test run: Hypothesis draws inputs in the trusted parent, a callee answers.

The callee is normally a sandboxed :class:`~slamcourse.sandbox.Worker`; the validator also uses
trusted in-process callees (misconception implementations from reference.py). Expected values are
computed here and never leave this process. Runs are deterministic: a fixed seed per exercise,
no example database, and the same explicit edge examples first.
"""

from __future__ import annotations

import copy
import hashlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from slamcourse.course.model import Tolerance
from slamcourse.errors import GraderError
from slamcourse.grading.returns import compare, to_plain
from slamcourse.sandbox import CallResult, LearnerFrame

MAX_RECORDED = 20  # failing inputs kept for recognising misconceptions


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


@dataclass
class Outcome:
    """What a run found: ``failure`` is the minimal (shrunk) failing input, if any."""

    examples: int = 0
    failure: Failure | None = None
    failures: list[Failure] = field(default_factory=list)
    seed: int = 0
    drawn: list[dict[str, Any]] = field(default_factory=list)  # inputs, in the order tried
    replayed: bool = False

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
) -> Outcome:
    """Run the property test; returns the outcome (never raises for learner behaviour)."""
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
        phases=(Phase.explicit, Phase.generate, Phase.shrink),
    )(test)
    test = fixed_seed(seed)(test)
    try:
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


def replay(
    *,
    inputs: Sequence[dict[str, Any]],
    signature: Sequence[str],
    returns: Any,
    tolerance: Tolerance,
    reference: Callable[..., Any],
    call: Callable[[Sequence[Any]], CallResult],
    seed: int,
) -> Outcome | None:
    """Check recorded inputs in order, without Hypothesis (see :mod:`.replay`).

    Returns the passing outcome, or a fatal one (timeout, crash: the same input the full run
    would stop at). Returns None at the first failing input: the caller then runs in full.
    """
    outcome = Outcome(seed=seed, replayed=True)
    for kwargs in inputs:
        outcome.examples += 1
        try:
            want = reference(**copy.deepcopy(kwargs))
        except Exception:
            return None  # the full run reports the reference's failure properly
        result = call([kwargs[name] for name in signature])
        if result.status in ("timeout", "crashed", "protocol_error"):
            outcome.failure = Failure(
                kwargs, want, None, result.error, result.status, stdout=result.stdout
            )
            return outcome
        if result.status != "ok" or compare(returns, result.value, want, tolerance) is not None:
            return None
    return outcome


def collect_failures(
    outcome: Outcome,
    *,
    inputs: Sequence[dict[str, Any]],
    signature: Sequence[str],
    returns: Any,
    tolerance: Tolerance,
    reference: Callable[..., Any],
    call: Callable[[Sequence[Any]], CallResult],
) -> None:
    """Add the inputs among ``inputs`` on which the callee returns a wrong value to
    ``outcome.failures`` (evidence for recognising a misconception; the verdict's reported
    failure stays the minimal one)."""
    seen = [f.kwargs for f in outcome.failures]
    for kwargs in inputs:
        if kwargs in seen or len(outcome.failures) >= MAX_RECORDED:
            continue
        try:
            want = reference(**copy.deepcopy(kwargs))
        except Exception:
            continue
        result = call([kwargs[name] for name in signature])
        if result.status != "ok":
            if result.status in ("timeout", "crashed", "protocol_error"):
                return
            continue
        if compare(returns, result.value, want, tolerance) is not None:
            outcome.failures.append(Failure(kwargs, want, result.value, "", "mismatch"))


def matching_misconception(
    outcome: Outcome,
    returns: Any,
    tolerance: Tolerance,
    candidates: Sequence[tuple[str, Callable[..., Any]]],
) -> str | None:
    """The id of the first misconception whose outputs equal the learner's on every recorded
    failing input (only inputs where the learner returned a value count)."""
    observed = [f for f in outcome.failures if f.kind == "mismatch"]
    if not observed:
        return None
    for mid, fn in candidates:
        try:
            if all(
                compare(returns, f.got, fn(**copy.deepcopy(f.kwargs)), tolerance) is None
                for f in observed
            ):
                return mid
        except Exception:  # a misconception undefined on this input does not match
            continue
    return None
