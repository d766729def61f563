"""The ``code`` kind: a Python function the learner writes, graded by property tests.

The learner's file runs in a sandboxed worker (:mod:`slamcourse.sandbox`) that only ever hands
back plain values; inputs are drawn, references computed and values compared here, in the
trusted parent (:mod:`slamcourse.grading`).
"""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar

from slamcourse.course import reference
from slamcourse.course.loader import read_course_file
from slamcourse.course.model import ExerciseSpec, Tolerance, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict, LineList
from slamcourse.errors import Problem
from slamcourse.kinds.base import Kind, problem, render
from slamcourse.verdict import Verdict, capitalised, engine_text, literal

CODE_TOLERANCE = Tolerance(rtol=1e-6, atol=1e-9)
MAX_SOURCE_BYTES = 256 * 1024
_ARGUMENT_FORMS = {"float": "range", "int": "int-range", "choice": "list"}
_IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
# ``limits:`` an exercise may raise (or lower) for its sandbox worker, with the largest value
# accepted for each (seconds, or bytes for memory): enough for a whole optimiser on a real graph,
# small enough that one check cannot hold a machine for long
LIMIT_MAXIMA: dict[str, float] = {
    "call_seconds": 120.0,
    "total_seconds": 300.0,
    "cpu_seconds": 300,
    "memory_bytes": 4 << 30,
}
_WHOLE_LIMITS = ("cpu_seconds", "memory_bytes")
STOPPED = {  # why the worker stopped a learner's calls (CallResult.stopped): (details key, verdict)
    "flooded": (
        "flooded",
        "Your function printed more than 1 MiB of output in one call (test input {at} of {n}), "
        "so grading stopped there: remove or shorten the print statements and check again.",
    ),
    "processes": (
        "left_running",
        "Your function returned while a process it started was still running (test input {at} "
        "of {n}), so grading stopped there: wait for every process it starts before returning "
        "(or start none).",
    ),
}


@dataclass(frozen=True)
class CodeOptions:
    function: str
    signature: tuple[str, ...]
    starter: Path
    solution: Path
    arguments: tuple[Any, ...]  # grading.strategies.Argument
    strategy: str | None
    strategy_line: int
    assume: tuple[str, ...]
    examples: tuple[dict[str, Any], ...]
    returns: Any
    max_examples: int
    tolerance: Tolerance
    limits: tuple[tuple[str, float], ...] = ()  # sandbox Limits overrides, e.g. call_seconds
    types: tuple[Any, ...] = ()  # grading.domains argument types, one per signature parameter
    valid: str | None = None  # reference.py function: is a derived boundary input in the domain
    valid_line: int = 0
    mutates: tuple[str, ...] = ()  # parameters the prompt allows the function to change in place
    judge: str | None = None  # reference.py function deciding instead of the tolerance
    judge_line: int = 0

    def sandbox_limits(self) -> Any:
        """The worker's :class:`~slamcourse.sandbox.Limits`: the defaults with this exercise's
        ``limits`` applied, or None when it has none (the defaults)."""
        from slamcourse.sandbox import Limits

        overrides: dict[str, Any] = dict(self.limits)  # whole numbers where Limits wants int
        return Limits(**overrides) if overrides else None

    def worker_request(self, source: str) -> tuple[Any, bool]:
        """What a check of ``source`` asks its worker factory for: the limits
        (:meth:`sandbox_limits`) and whether the source names scipy
        (:func:`~slamcourse.grading.pool.uses_scipy`). A batch announces the same ahead
        (:meth:`~slamcourse.engine.Engine.expect_code`), so it is computed here only."""
        from slamcourse.grading.pool import uses_scipy

        return self.sandbox_limits(), uses_scipy(source)

    def may_run_long(self) -> bool:
        """Whether the exercise gives a learner's function more time than the sandbox's
        defaults (a whole data set): how long its check takes then depends most on the
        learner's method (a dense solve of INTEL took 10 s where the sparse one took 0.1 s)."""
        from slamcourse.sandbox import Limits

        default = Limits()
        return any(
            value > getattr(default, name)
            for name, value in self.limits
            if name in ("call_seconds", "total_seconds", "cpu_seconds")
        )


class CodeKind(Kind):
    """Write a function; Hypothesis checks it against the reference on ≥ 200 inputs."""

    name: ClassVar[str] = "code"
    keys: ClassVar[dict[str, bool]] = {
        "function": True,
        "signature": True,
        "starter": True,
        "solution": True,
        "arguments": False,
        "strategy": False,
        "assume": False,
        "examples": False,
        "returns": True,
        "max_examples": False,
        "limits": False,
        "types": False,
        "valid": False,
        "mutates": False,
        "judge": False,
    }
    misconception_key: ClassVar[str | None] = "function"

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> CodeOptions:
        from slamcourse.grading.returns import parse_returns
        from slamcourse.grading.strategies import Argument

        super().parse(spec, raw, check)
        function = str(check.typed(raw, "function", str, "f"))
        if not _IDENT.match(function):
            check.add(raw.line_of("function"), f"'function: {function}' is not a Python name")
        signature = tuple(str(s) for s in check.typed(raw, "signature", list, []))
        for name in signature:
            if not _IDENT.match(name):
                check.add(
                    raw.line_of("signature"), f"signature entry '{name}' is not a Python name"
                )
        paths = {}
        for key in ("starter", "solution"):
            rel = str(check.typed(raw, key, str, ""))
            paths[key] = spec.path.parent / rel
            if rel and not paths[key].is_file():
                check.add(
                    raw.line_of(key),
                    f"'{key}: {rel}' does not exist next to the exercise (looked for {paths[key]})",
                )
        arguments: list[Argument] = []
        data = raw.get("arguments")
        if data is not None:
            mapping = check.mapping(data, raw.line_of("arguments"), "'arguments'")
            for name, value in (mapping or {}).items():
                line = mapping.line_of(name) if mapping else raw.line
                item = check.mapping(value, line, f"argument '{name}'")
                if item is None:
                    continue
                check.keys(item, _ARGUMENT_FORMS, (), f"argument '{name}'")
                found = check.distribution(item, _ARGUMENT_FORMS, f"argument '{name}'")
                if found is None:
                    continue
                arguments.append(Argument(name, found[0], found[1], line))
            if set(a.name for a in arguments) != set(signature):
                check.add(
                    raw.line_of("arguments"),
                    f"'arguments' must describe exactly the "
                    f"signature's parameters ({', '.join(signature)})",
                )
        strategy = check.typed(raw, "strategy", str)
        if (strategy is None) == (data is None):
            check.add(
                raw.line,
                "a code exercise needs either 'arguments' (simple ranges) or "
                "'strategy: <function in reference.py returning a Hypothesis strategy>'",
            )
        examples = []
        items = check.typed(raw, "examples", list, [])
        for i, item in enumerate(items):
            line = items.line_of(i) if isinstance(items, LineList) else raw.line
            ex = check.mapping(item, line, "an example")
            if ex is None:
                continue
            if set(ex) != set(signature):
                check.add(line, f"an example must give exactly {', '.join(signature)}")
                continue
            for arg in arguments:
                problem_text = _outside_domain(arg, ex[arg.name])
                if problem_text:
                    check.add(line, f"example value {arg.name}: {problem_text}")
            examples.append(_plain(ex))
        returns = parse_returns(raw.get("returns"))
        if returns is None:
            check.add(
                raw.line_of("returns"),
                "'returns' must be number, integer, angle, boolean, "
                "array, or a list of the scalar ones such as [number, angle]",
            )
        max_examples = check.typed(raw, "max_examples", int, 200)
        tol = spec.tolerance if "tolerance" in raw else CODE_TOLERANCE
        limits = _parse_limits(raw, check)
        types = _parse_types(raw, signature, arguments, check)
        judge = check.typed(raw, "judge", str)
        if judge is not None and raw.get("misconceptions"):
            check.add(
                raw.line_of("judge"),
                "a judged exercise names what is wrong in its judge's message: "
                "drop its 'misconceptions' (a learner's random values never equal one's)",
            )
        return CodeOptions(
            function,
            signature,
            paths["starter"],
            paths["solution"],
            tuple(arguments),
            strategy,
            raw.line_of("strategy"),
            tuple(str(a) for a in check.typed(raw, "assume", list, [])),
            tuple(examples),
            returns,
            max_examples,
            tol,
            limits,
            types=types,
            valid=_parse_valid(raw, check),
            valid_line=raw.line_of("valid"),
            mutates=_parse_mutates(raw, signature, check),
            judge=judge,
            judge_line=raw.line_of("judge"),
        )

    # ------------------------------------------------------------------ grading
    def expected(self, spec: ExerciseSpec, variant: Variant) -> Any:
        """Code exercises have no single answer; the explanation sees the function's name."""
        return spec.options.function

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        opts: CodeOptions = spec.options
        return {
            "type": "code",
            "function": opts.function,
            "signature": list(opts.signature),
            "starter": opts.starter.read_text(encoding="utf-8", errors="replace"),
        }

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        """How to answer and the rules every code prompt states, derived from the exercise's
        own options so they are always true: imports, tolerance, arguments left unchanged."""
        opts: CodeOptions = spec.options
        sig = f"{opts.function}({', '.join(opts.signature)})"
        return (
            f"Write `{sig}`, then submit it for checking. {IMPORTS_RULE} "
            f"{judge_rule(opts) or tolerance_rule(opts.returns, opts.tolerance)} "
            f"{mutation_rule(opts)}"
        )

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        return self.check_source(spec, answer, f"{spec.options.function}.py")

    def strategy(self, spec: ExerciseSpec) -> Any:
        from slamcourse.grading.strategies import strategy_for

        opts: CodeOptions = spec.options
        if opts.strategy:
            return reference.function(spec, opts.strategy, opts.strategy_line)()
        return strategy_for(opts.arguments, opts.assume)

    def check_source(
        self,
        spec: ExerciseSpec,
        source: str,
        filename: str,
        *,
        require_isolation: bool = False,
        spawn: Any = None,
        hidden_seed: int | None = None,
        shrink: bool = True,
        tests: Any = None,
        max_failures: int | None = None,
    ) -> Verdict:
        """Grade learner ``source`` in a fresh sandboxed worker: ``spawn(limits, scipy=...)``
        hands one out (the engine's pool or a submission's zygote; ``limits`` is the
        exercise's own, or None for the defaults; ``scipy``, whether the source uses scipy);
        without it, one is spawned here.

        ``tests``: a prebuilt :class:`~slamcourse.grading.testset.TestSet` (a batch builds each
        exercise's once, hidden inputs included); without it the visible test set is built
        here, plus the inputs drawn with ``hidden_seed`` if given (grading mode). ``shrink``
        lets Hypothesis shrink a failure on a visible input to a minimal one (a learner's check;
        the batch grader and the validator report the first failing input instead: same
        status). ``max_failures``: stop after that many failing inputs (default: as many as a
        verdict reports; the validator asks for 1).
        """
        from slamcourse.answers.text import unreadable_at
        from slamcourse.errors import GraderError
        from slamcourse.grading import testset
        from slamcourse.sandbox import Worker

        bad = unreadable_at(source)
        if bad is not None:  # the answers' decoding policy, said per line for a file
            line = source.count("\n", 0, bad[0]) + 1
            return Verdict.unreadable(
                f"{filename}:{line}: a character is not text ({bad[1]}); save the file as UTF-8"
            )
        if len(source.encode("utf-8", "replace")) > MAX_SOURCE_BYTES:
            return Verdict.unreadable(f"{filename} is larger than {MAX_SOURCE_BYTES // 1024} KiB")
        opts: CodeOptions = spec.options
        limits, scipy = opts.worker_request(source)
        timing = [0.0]  # seconds inside the learner's calls
        try:
            # start the interpreter first: it imports numpy while the test set is built
            if spawn is not None:
                worker = spawn(limits, scipy=scipy)
            else:
                worker = Worker.spawn(limits=limits, require_isolation=require_isolation)
            with worker:
                if tests is None:
                    seeds = [hidden_seed] if hidden_seed is not None else []
                    tests = testset.build(spec, hidden_seeds=seeds)
                loaded = worker.load(source, filename, opts.function, opts.signature)
                if not loaded.ok:
                    return _load_verdict(loaded, filename, opts)
                verdict = self._grade(
                    spec,
                    tests,
                    worker.call_many,
                    worker.call if shrink else None,
                    filename,
                    isolation=worker.isolation.level,
                    output_cut=loaded.output_cut,
                    timing=timing,
                    max_failures=max_failures,
                )
                return replace(verdict, learner_seconds=timing[0])
        except GraderError as exc:  # the grader's fault, said as such; no attempt is counted
            return Verdict("error", 0.0, f"Not graded (a problem on the grader's side): {exc}")

    def _grade(
        self,
        spec: ExerciseSpec,
        tests: Any,
        call_many: Any,
        call: Any,
        filename: str,
        *,
        isolation: str,
        output_cut: bool = False,
        timing: list[float] | None = None,
        max_failures: int | None = None,
    ) -> Verdict:
        """One pass over the test set ``tests`` (see :mod:`slamcourse.grading.testset`); with
        ``call`` (a single-call function), a failure on a visible input is then shrunk by a
        full Hypothesis run, which reports the smallest failing input it finds."""
        from slamcourse.grading.properties import MAX_RECORDED, matching_misconception, run
        from slamcourse.grading.returns import show_exact, show_pair, to_plain
        from slamcourse.grading.testset import input_key, run_cases

        opts: CodeOptions = spec.options
        ref = reference.function(spec, spec.reference or "", spec.reference_line)
        # a failing input of a whole data set (intel/whole-graph: a 216 kB g2o text) makes
        # Hypothesis warn on stderr about its repr; the verdict shows the input abridged anyway
        warnings.filterwarnings("ignore", message="Generating overly large repr")
        outcome, _cases = run_cases(
            tests,
            call_many,
            signature=opts.signature,
            returns=opts.returns,
            tolerance=opts.tolerance,
            mutable=opts.mutates,
            max_failures=MAX_RECORDED if max_failures is None else max_failures,
            stop_worker=call is None,  # a shrinking check still needs its worker
            judge=reference.function(spec, opts.judge, opts.judge_line) if opts.judge else None,
        )
        outcome.output_cut = outcome.output_cut or output_cut
        if timing is not None:
            timing[0] += outcome.call_seconds
        failure = outcome.failure
        case = outcome.failure_case
        visible_total = len(tests.visible)
        hidden_run = sum(1 for c in tests.cases[: outcome.examples] if c.hidden)
        details: dict[str, Any] = {
            "examples": outcome.examples - hidden_run,
            "seed": tests.seed,
            "isolation": isolation,
        }
        if tests.hidden_runs:
            details["hidden_examples"] = hidden_run
            details["hidden_runs"] = tests.hidden_runs
            details["hidden_failed"] = len(outcome.hidden_failed)
        shrunk = False
        if (
            failure is not None
            and call is not None
            and not opts.judge  # a judge's verdict on one input says nothing of smaller ones
            and not case.hidden
            and failure.kind in ("mismatch", "raised")
        ):
            full = run(
                strategy=self.strategy(spec),
                examples=opts.examples,
                signature=opts.signature,
                returns=opts.returns,
                tolerance=opts.tolerance,
                reference=ref,
                call=call,
                max_examples=opts.max_examples,
                seed=tests.seed,
            )
            if full.failure is not None and full.failure.kind in ("mismatch", "raised"):
                key = input_key(full.failure.kwargs)
                known = [f for f in outcome.failures if input_key(f.kwargs) != key]
                outcome.failure = failure = full.failure
                outcome.failures = [full.failure, *known][:MAX_RECORDED]
                same = [c for c in tests.cases if input_key(c.kwargs) == key]
                if same:  # Hypothesis ended on an input of the test set (e.g. an example)
                    case = same[0]
                    failure = outcome.failure = replace(failure, origin=case.origin)
                else:
                    shrunk = True
        note = ""
        if outcome.output_cut:
            details["output_cut"] = True
            note = "\n\nYour code printed a lot: output beyond the first 1 MiB per stream was cut."
        if outcome.stopped is not None:  # (the checks stopped there: said, unless one failed)
            reason, at = outcome.stopped
            key, message = STOPPED[reason]
            details[key] = at
            if failure is None:
                return Verdict.wrong(message.format(at=at, n=len(tests.cases)), **details)
        if failure is None:
            return Verdict.ok(
                f"All {visible_total} test inputs passed, edge cases and boundary inputs "
                f"included.{note}",
                **details,
            )
        if case is not None and case.hidden and not shrunk:
            details["hidden"] = True
            what = {
                "mismatch": "returns a wrong value",
                "raised": "raises an exception",
                "mutated": "changes its arguments in place",
                "timeout": "does not finish in time",
            }.get(failure.kind, "stops the grader's worker")
            return Verdict.wrong(
                f"All {visible_total} test inputs your own check uses passed, but on an input "
                f"the hidden checks drew (which the prompt allows) `{opts.function}` "
                f"{what}. Look for a case you did not handle.{note}",
                **details,
            )
        args = ", ".join(f"{k}={show_exact(v)}" for k, v in failure.kwargs.items())
        details.update(
            input={k: to_plain(v) for k, v in failure.kwargs.items()},  # JSON: ndarrays as lists
            expected=to_plain(failure.expected),
            got=failure.got,
            frames=[
                {"file": filename, "line": f.line, "text": f.text, "function": f.function}
                for f in failure.frames
            ],
        )
        if failure.origin.startswith("boundary"):
            details["boundary"] = failure.origin.split(": ", 1)[-1]
        call_text = f"{opts.function}({args})"
        if failure.kind == "timeout":
            return Verdict(
                "timeout",
                0.0,
                f"`{call_text}` did not finish in time ({failure.message})."
                f" Look for a loop that never ends.{note}",
                details=details,
            )
        if failure.kind in ("crashed", "protocol_error"):
            from slamcourse.sandbox.runner import FLOOD_MESSAGE

            advice = (
                "Print less."
                if failure.message.startswith(FLOOD_MESSAGE)
                else "Do not exit or write to the grader's channels; return the value."
            )
            return Verdict.wrong(
                f"`{call_text}` stopped the grader's worker: {failure.message}. {advice}{note}",
                **details,
            )
        if failure.kind == "raised":
            where = "".join(f"\n- `{filename}:{f.line}`: `{f.text}`" for f in failure.frames[-3:])
            text = f"`{call_text}` raised {_sentence(literal(failure.message))}" + (
                f"\n{where}" if where else ""
            )
        elif failure.kind == "mutated":
            text = f"`{call_text}`: {_sentence(engine_text(failure.message))}"
        elif opts.judge:  # the reference's value is one right answer of many: not "expected"
            got_text = show_pair(to_plain(failure.expected), failure.got)[1]
            text = f"Wrong result for `{call_text}`: got `{got_text}`. " + _sentence(
                engine_text(failure.message)
            )
        else:
            want_text, got_text = show_pair(to_plain(failure.expected), failure.got)
            text = f"Wrong result for `{call_text}`: expected `{want_text}`, got `{got_text}`."
            if not _restates_values(failure.message):  # where (an entry), what kind, a shape
                text += f" {_sentence(engine_text(failure.message))}"
        tried = f"{outcome.examples} test input{'s' if outcome.examples != 1 else ''}"
        if shrunk:
            text += f"\n\nThe grader shrank the failure to this small input ({tried} run)."
        elif failure.origin == "example":
            text += f"\n\nThis is one of the exercise's fixed edge cases ({tried} run)."
        elif failure.origin.startswith("boundary"):
            text += (
                f"\n\nA boundary input of the declared argument types "
                f"({details['boundary']}; {tried} run)."
            )
        else:
            text += f"\n\nThe first failing input found ({tried} run)."
        text += note
        candidates = [
            (m.id, reference.function(spec, m.function or "", m.line)) for m in spec.misconceptions
        ]
        found = matching_misconception(outcome, opts.returns, opts.tolerance, candidates)
        if found:
            m = next(m for m in spec.misconceptions if m.id == found)
            message = render(spec, m.message, Variant(0, {}))
            return Verdict.wrong(f"{text}\n\n{message}", misconception=found, **details)
        return Verdict.wrong(text, **details)

    # ------------------------------------------------------------------ validation
    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        """Solution passes, starter fails, every mutant fails, every correct variant passes
        (each through the real sandbox, a fresh worker each), every misconception fails and is
        recognised as itself; all against one test set, built once."""
        from slamcourse.grading import testset
        from slamcourse.grading.properties import TrustedCallee

        problems: list[Problem] = []
        if variant.seed != 0:
            return problems  # Hypothesis covers the inputs; one run is enough
        tests = testset.build(spec)
        problems += self.check_submissions(spec, tests=tests)
        problems += self.boundary_problems(spec, tests)
        for m in spec.misconceptions:
            callee = TrustedCallee(reference.function(spec, m.function or "", m.line))
            verdict = self._grade(
                spec,
                tests,
                lambda many, callee=callee: [callee.call(args) for args in many],
                callee.call,
                "reference.py",
                isolation="trusted",
            )
            if verdict.passed:
                problems.append(
                    problem(
                        spec,
                        m.line,
                        f"misconception '{m.id}' passes every "
                        "test input; add an example where it goes wrong",
                    )
                )
            elif verdict.misconception != m.id:
                problems.append(
                    problem(
                        spec,
                        m.line,
                        f"misconception '{m.id}' fails but is "
                        f"recognised as {verdict.misconception or 'nothing'}",
                    )
                )
        return problems

    def boundary_problems(self, spec: ExerciseSpec, tests: Any) -> list[Problem]:
        """Every boundary class the declared argument types call for is drawn (at least one
        input of it lies in the exercise's domain), and the exercise declares its types."""
        opts: CodeOptions = spec.options
        if not opts.types:
            return [
                problem(
                    spec,
                    spec.line,
                    "no 'types:' for the arguments, so no boundary inputs are drawn; declare "
                    "what each argument is (angle, pose, covariance, count, g2o, …; see "
                    "docs/authoring.md, 'Argument types and boundary inputs')",
                )
            ]
        from slamcourse.grading.domains import boundary_classes

        missing = sorted(set(boundary_classes(opts.types)) - set(tests.boundary_classes))
        if not missing:
            return []
        return [
            problem(
                spec,
                spec.line,
                f"no input of the boundary class{'es' if len(missing) > 1 else ''} "
                f"{', '.join(missing)} lies in the exercise's domain (each derived input was "
                "outside a declared range, rejected by 'valid', or undefined for the "
                "reference); narrow the argument's type or widen the strategy",
            )
        ]

    def check_submissions(
        self, spec: ExerciseSpec, *, jobs: int = 2, tests: Any = None
    ) -> list[Problem]:
        """Grade the solution, the starter, the mutants and the correct variants exactly as a
        learner's files, ``jobs`` at a time, against one test set (``tests``, or built here):
        the references are computed once, and each file gets a fresh worker forked from one
        zygote, so no file pays an interpreter start."""
        from concurrent.futures import ThreadPoolExecutor

        from slamcourse.course.loader import relpath
        from slamcourse.grading import testset
        from slamcourse.sandbox import Zygote

        opts: CodeOptions = spec.options
        if tests is None:
            tests = testset.build(spec)
        mutants, variants = submission_files(spec)
        problems: list[Problem] = []
        runs: list[tuple[str, Path, bool, str]] = [
            ("starter", opts.starter, False, ""),
        ]
        for kind_, paths, want_pass in (("mutant", mutants, False), ("variant", variants, True)):
            for path in paths:
                label = _first_line_label(path, SUBMISSION_TAGS[kind_])
                if label is None:
                    problems.append(
                        Problem(
                            relpath(path, spec.course_root),
                            1,
                            f"the first line of a {kind_} must be "
                            f"'# {SUBMISSION_TAGS[kind_]}: <{SUBMISSION_HELP[kind_]}>'",
                        )
                    )
                runs.append((kind_, path, want_pass, label or ""))

        runs.insert(0, ("solution", opts.solution, True, ""))
        # the course's own files: one zygote serves them all (a learner's never share one)
        with Zygote.spawn() as zygote:

            def grade(path: Path) -> Verdict:
                source = read_course_file(path, spec.course_root)
                return self.check_source(
                    spec,
                    source,
                    path.name,
                    shrink=False,
                    tests=tests,
                    spawn=lambda limits, scipy: zygote.worker(limits),
                    max_failures=1,  # whether it passes is all the validator asks
                )

            with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
                verdicts = list(pool.map(lambda r: grade(r[1]), runs))
        solution = verdicts.pop(0)
        runs.pop(0)
        if not solution.passed:
            problems.append(
                problem(
                    spec,
                    spec.line,
                    f"the solution {opts.solution.name} fails: {_first(solution.feedback)}",
                )
            )
        for (kind_, path, _want, label), verdict in zip(runs, verdicts, strict=True):
            if kind_ == "starter":
                if verdict.passed:
                    problems.append(
                        problem(
                            spec,
                            spec.line,
                            f"the starter {path.name} passes: {_first(verdict.feedback)}",
                        )
                    )
                continue
            where = relpath(path, spec.course_root)
            if kind_ == "mutant" and verdict.passed:
                problems.append(
                    Problem(
                        where,
                        1,
                        f"this mutant passes every test input ({label or 'no mistake named'}); "
                        "add an edge example to the exercise's 'examples' where it goes wrong",
                    )
                )
            elif kind_ == "mutant" and verdict.status in ("invalid", "error"):
                problems.append(
                    Problem(
                        where,
                        1,
                        f"this mutant is not graded as a wrong answer but as "
                        f"{verdict.status}: {_first(verdict.feedback)}",
                    )
                )
            elif kind_ == "variant" and not verdict.passed:
                problems.append(
                    Problem(
                        where,
                        1,
                        f"this correct variant ({label or 'no method named'}) fails: "
                        f"{_first(verdict.feedback)}",
                    )
                )
        return problems


IMPORTS_RULE = "You may import the Python standard library, numpy and scipy (nothing else)."


def tolerance_rule(returns: Any, tol: Tolerance) -> str:
    """One sentence: how returned values are compared (what ``grading.returns`` does)."""
    kinds = {returns} if isinstance(returns, str) else set(returns)
    window = f"|got − expected| ≤ {tol.atol:g} + {tol.rtol:g}·|expected|"
    parts = []
    if kinds & {"number", "angle", "array"}:
        where = " per entry" if "array" in kinds or len(kinds) > 1 else ""
        parts.append(f"numbers are accepted when {window}{where}")
    if "angle" in kinds:
        parts.append("angles modulo 2π")
    if kinds & {"integer", "boolean"}:
        parts.append(
            "whole numbers and booleans must be exact"
            if {"integer", "boolean"} <= kinds
            else ("whole numbers must be exact" if "integer" in kinds else "booleans must be exact")
        )
    text = "; ".join(parts)
    return f"Results: {text}." if text else ""


def judge_rule(opts: CodeOptions) -> str:
    """With a ``judge``: one sentence saying that a statistical test decides (the prompt states
    the test and its probabilities); else an empty string."""
    if not opts.judge:
        return ""
    return (
        "Results: judged by the test the prompt states (any correct method passes with the "
        "probability it states), not compared with one expected value."
    )


def mutation_rule(opts: CodeOptions) -> str:
    """One sentence: which arguments the function may change in place (by default none)."""
    if not opts.mutates:
        return "Leave the arguments as given: return new values, never change an argument."
    names = ", ".join(f"`{n}`" for n in opts.mutates)
    return f"The function may change {names} in place; leave the other arguments as given."


SUBMISSION_TAGS = {"mutant": "mistake", "variant": "method"}
SUBMISSION_HELP = {"mutant": "the plausible mistake", "variant": "the method"}


def submission_files(spec: ExerciseSpec) -> tuple[list[Path], list[Path]]:
    """The exercise's mutants (``mutants/<slug>/*.py``) and correct variants
    (``variants/<slug>/*.py``), next to its YAML file, sorted by name."""
    folder, slug = spec.path.parent, spec.path.stem
    return (
        sorted((folder / "mutants" / slug).glob("*.py")),
        sorted((folder / "variants" / slug).glob("*.py")),
    )


def _first_line_label(path: Path, tag: str) -> str | None:
    """What follows ``# <tag>:`` on the file's first line, or None."""
    try:
        with path.open(encoding="utf-8", errors="replace") as handle:
            first = handle.readline().strip()
    except OSError:
        return None
    prefix = f"# {tag}:"
    if not first.startswith(prefix) or not first[len(prefix) :].strip():
        return None
    return first[len(prefix) :].strip()


def _first(feedback: str) -> str:
    lines = feedback.strip().splitlines()
    return lines[0] if lines else ""


def _load_verdict(loaded: Any, filename: str, opts: CodeOptions) -> Verdict:
    sig = f"def {opts.function}({', '.join(opts.signature)})"
    status = loaded.status
    if status == "syntax_error":
        where = f"{filename}:{loaded.line}" if loaded.line else filename
        return Verdict.unreadable(f"{where}: syntax error: {loaded.message}")
    if status == "missing_function":
        found = f" (it defines {', '.join(loaded.found)})" if loaded.found else ""
        return Verdict.unreadable(
            f"{filename} has no function `{opts.function}`{found}; write `{sig}:`"
        )
    if status == "not_callable":
        return Verdict.unreadable(
            f"`{opts.function}` in {filename} is not a function; write `{sig}:`"
        )
    if status == "signature":
        return Verdict.unreadable(
            f"`{opts.function}` must take {len(opts.signature)} parameters "
            f"({', '.join(opts.signature)}); {loaded.message}".rstrip("; ")
        )
    if status == "import_error":
        where = "".join(
            f"\n  {literal(filename)}:{f.line}: {literal(f.text, line_start=False)}"
            for f in loaded.frames[-3:]
        )
        return Verdict.wrong(
            f"{literal(filename)} raised while it was loaded: {literal(loaded.message)}{where}"
        )
    if status == "timeout":
        return Verdict(
            "timeout",
            0.0,
            f"{filename} did not finish loading in time: is there a "
            "loop at the top level of the file?",
        )
    return Verdict.wrong(
        f"{literal(filename)} stopped the grader's worker while loading: {literal(loaded.message)}"
    )


def _parse_limits(raw: LineDict, check: Checker) -> tuple[tuple[str, float], ...]:
    """``limits: {call_seconds: 90, ...}``: overrides of the sandbox's per-worker limits, each
    a positive number no larger than :data:`LIMIT_MAXIMA` (whole numbers for CPU and memory)."""
    data = raw.get("limits")
    if data is None:
        return ()
    mapping = check.mapping(data, raw.line_of("limits"), "'limits'")
    if mapping is None:
        return ()
    check.keys(mapping, LIMIT_MAXIMA, (), "'limits'")
    found: list[tuple[str, float]] = []
    for name, value in mapping.items():
        if name not in LIMIT_MAXIMA:
            continue
        line, most = mapping.line_of(name), LIMIT_MAXIMA[name]
        whole = name in _WHOLE_LIMITS
        number = (
            isinstance(value, int) if whole else isinstance(value, int | float)
        ) and not isinstance(value, bool)
        if not number:
            kind = "a whole number" if whole else "a number"
            hint = (
                " (YAML reads '1.0e6' as text: write 1000000.0)" if isinstance(value, str) else ""
            )
            check.add(line, f"limit '{name}' must be {kind}, not {value!r}{hint}")
        elif not 0 < value <= most:
            shown = (
                f"{int(most)} ({int(most) >> 30} GiB)" if name == "memory_bytes" else f"{most:g}"
            )
            check.add(line, f"limit '{name}' must be above 0 and at most {shown}, not {value!r}")
        else:
            found.append((str(name), value))
    return tuple(sorted(found))


def _parse_types(
    raw: LineDict, signature: tuple[str, ...], arguments: list[Any], check: Checker
) -> tuple[Any, ...]:
    """``types:`` (what each parameter is: grading.domains), checked against the signature
    and the examples; without it, the types that ``arguments:`` ranges imply (float → real,
    int → count, choice → choice), so simple exercises get boundary inputs too."""
    from slamcourse.grading import domains

    if "types" not in raw:
        return domains.types_from_arguments(arguments)
    types = domains.parse_types(raw["types"], signature, check, line=raw.line_of("types"))
    items = raw.get("examples")
    if isinstance(items, list):
        for i, item in enumerate(items):
            if not isinstance(item, dict):
                continue
            line = items.line_of(i) if isinstance(items, LineList) else raw.line
            for t in types:
                if t.name in item:
                    why = domains.outside(t, item[t.name])
                    if why:
                        check.add(line, f"example value {t.name}: {why}")
    return types


def _parse_valid(raw: LineDict, check: Checker) -> str | None:
    """``valid: <function in reference.py>``: which derived boundary inputs lie in the
    exercise's domain (grading.domains.parse_valid)."""
    from slamcourse.grading.domains import parse_valid

    return parse_valid(raw.get("valid"), raw.line_of("valid"), check)


def _parse_mutates(raw: LineDict, signature: tuple[str, ...], check: Checker) -> tuple[str, ...]:
    """``mutates: [name, …]``: the parameters the function may change in place."""
    from slamcourse.grading.domains import parse_mutates

    return parse_mutates(raw.get("mutates"), raw.line_of("mutates"), signature, check)


def _outside_domain(arg: Any, value: Any) -> str | None:
    """Why an edge example's value lies outside the argument's declared domain (the prompt's
    stated domain: graders draw only from it), or None."""
    if arg.dist == "choice":
        return None if value in arg.args else f"{value!r} is not one of {list(arg.args)}"
    if isinstance(value, bool) or not isinstance(value, int | float):
        return (
            f"{value!r} is not a number (YAML reads '1.0e6' as text: write 1000000.0)"
            if isinstance(value, str)
            else f"{value!r} is not a number"
        )
    if arg.dist == "int" and not isinstance(value, int):
        return f"{value!r} is not a whole number"
    low, high = arg.args[0], arg.args[1]
    if not low <= value <= high:
        return f"{value!r} is outside the declared range [{low}, {high}]; widen the range or fix it"
    return None


_VALUE_COMPARISON = re.compile(r"expected (\S+)(?: \(mod 2π\))?, got (\S+)")


def _restates_values(message: str) -> bool:
    """The mismatch message only compares two values the feedback already shows ("expected 1.5,
    got 2"), not what kind of value came back ("expected a number, got None (did you forget to
    return?)", "expected an array of shape 2×2, got a scalar") nor where ("entry [1]: …")."""
    found = _VALUE_COMPARISON.fullmatch(message)
    return found is not None and all(_is_value(text) for text in found.groups())


def _is_value(text: str) -> bool:
    if text in ("True", "False"):
        return True
    try:
        float(text)
    except ValueError:
        return False
    return True


def _sentence(text: str) -> str:
    """A sentence: capitalised unless it starts with code or a file name, with a full stop."""
    text = text.strip()
    if not text:
        return ""
    return capitalised(text) + ("" if text.endswith((".", "!", "?")) else ".")


def _plain(data: Any) -> Any:
    if isinstance(data, dict):
        return {str(k): _plain(v) for k, v in data.items()}
    if isinstance(data, list):
        return [_plain(v) for v in data]
    return data


def read_source(path: Path) -> str:
    """The learner's file as text; unreadable files are a usage problem, not a verdict."""
    from slamcourse.errors import UsageError

    try:
        data = path.read_bytes()
    except OSError as exc:
        raise UsageError(f"cannot read {path}: {exc.strerror}") from None
    return data.decode("utf-8", errors="replace")
