"""The ``code`` kind: a Python function the learner writes, graded by property tests.

The learner's file runs in a sandboxed worker (:mod:`slamcourse.sandbox`) that only ever hands
back plain values; inputs are drawn, references computed and values compared here, in the
trusted parent (:mod:`slamcourse.grading`).
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

from slamcourse.course import reference
from slamcourse.course.loader import read_course_file
from slamcourse.course.model import ExerciseSpec, Tolerance, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict, LineList
from slamcourse.errors import Problem
from slamcourse.kinds.base import Kind, problem, render
from slamcourse.verdict import Verdict

CODE_TOLERANCE = Tolerance(rtol=1e-6, atol=1e-9)
MAX_SOURCE_BYTES = 256 * 1024
_ARGUMENT_FORMS = {"float": "range", "int": "int-range", "choice": "list"}
_IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


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
        sig = f"{spec.options.function}({', '.join(spec.options.signature)})"
        return f"Write `{sig}`, then submit it for checking."

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
        seed: int | None = None,
    ) -> Verdict:
        """Grade learner ``source`` in a fresh sandboxed worker: ``spawn()`` hands one out (the
        engine's pool); without it one is spawned here.

        ``seed``: draw the property-test inputs with this Hypothesis seed instead of the
        exercise's fixed one (the batch grader's hidden checks); such a run neither replays nor
        records inputs."""
        from slamcourse.answers.text import unreadable_at
        from slamcourse.errors import GraderError
        from slamcourse.sandbox import Worker

        bad = unreadable_at(source)
        if bad is not None:  # the answers' decoding policy, said per line for a file
            line = source.count("\n", 0, bad[0]) + 1
            return Verdict.unreadable(
                f"{filename}:{line}: a character is not text ({bad[1]}); save the file as UTF-8"
            )
        if len(source.encode("utf-8", "replace")) > MAX_SOURCE_BYTES:
            return Verdict.unreadable(f"{filename} is larger than {MAX_SOURCE_BYTES // 1024} KiB")
        try:
            if spawn is not None:
                worker = spawn()
            else:  # start the interpreter now; it imports numpy while we prepare
                worker = Worker.spawn(require_isolation=require_isolation)
            with worker:
                opts: CodeOptions = spec.options
                loaded = worker.load(source, filename, opts.function, opts.signature)
                if not loaded.ok:
                    return _load_verdict(loaded, filename, opts)
                return self._grade(
                    spec,
                    worker.call,
                    None,
                    filename,
                    isolation=worker.isolation.level,
                    use_recording=seed is None,
                    seed=seed,
                )
        except GraderError as exc:  # the grader's fault, said as such; no attempt is counted
            return Verdict("error", 0.0, f"Not graded (a problem on the grader's side): {exc}")

    def _grade(
        self,
        spec: ExerciseSpec,
        call: Any,
        strategy: Any,
        filename: str,
        *,
        isolation: str,
        use_recording: bool = True,
        seed: int | None = None,
    ) -> Verdict:
        from slamcourse.grading import replay as recording
        from slamcourse.grading.properties import (
            collect_failures,
            exercise_seed,
            matching_misconception,
            run,
        )
        from slamcourse.grading.properties import replay as replay_inputs

        opts: CodeOptions = spec.options
        ref = reference.function(spec, spec.reference or "", spec.reference_line)
        seed = exercise_seed(spec.id) if seed is None else seed
        key = recording.recording_key(spec, seed, opts.max_examples)
        inputs = recording.load(key) if use_recording else None
        outcome = None
        if inputs:
            outcome = replay_inputs(
                inputs=inputs,
                signature=opts.signature,
                returns=opts.returns,
                tolerance=opts.tolerance,
                reference=ref,
                call=call,
                seed=seed,
            )
        if outcome is None:
            outcome = run(
                strategy=strategy if strategy is not None else self.strategy(spec),
                examples=opts.examples,
                signature=opts.signature,
                returns=opts.returns,
                tolerance=opts.tolerance,
                reference=ref,
                call=call,
                max_examples=opts.max_examples,
                seed=seed,
            )
            if outcome.passed and use_recording:
                recording.save(key, outcome.drawn)
        details: dict[str, Any] = {
            "examples": outcome.examples,
            "seed": outcome.seed,
            "isolation": isolation,
        }
        failure = outcome.failure
        if failure is None:
            return Verdict.ok(
                f"All {outcome.examples} test inputs passed, edge cases included.", **details
            )
        from slamcourse.grading.returns import show, to_plain

        args = ", ".join(f"{k}={show(v)}" for k, v in failure.kwargs.items())
        details.update(
            input=failure.kwargs,
            expected=to_plain(failure.expected),
            got=failure.got,
            frames=[
                {"file": filename, "line": f.line, "text": f.text, "function": f.function}
                for f in failure.frames
            ],
        )
        call_text = f"{opts.function}({args})"
        if failure.kind == "timeout":
            return Verdict(
                "timeout",
                0.0,
                f"{call_text} did not finish in time ({failure.message})."
                " Look for a loop that never ends.",
                details=details,
            )
        if failure.kind in ("crashed", "protocol_error"):
            return Verdict.wrong(
                f"{call_text} stopped the grader's worker: {failure.message}. "
                "Do not exit or write to the grader's channels; return the value.",
                **details,
            )
        if failure.kind == "raised":
            where = "".join(f"\n- `{filename}:{f.line}`: `{f.text}`" for f in failure.frames[-3:])
            text = f"`{call_text}` raised {_sentence(failure.message)}" + (
                f"\n{where}" if where else ""
            )
        else:
            text = (
                f"Wrong result for `{call_text}`:\n\n"
                f"- expected `{show(to_plain(failure.expected))}`\n"
                f"- got `{show(failure.got)}`\n\n{_sentence(failure.message)}"
            )
        tried = f"{outcome.examples} test input{'s' if outcome.examples != 1 else ''}"
        if any(failure.kwargs == ex for ex in opts.examples):
            text += f"\n\nThis is one of the exercise's fixed edge cases ({tried} run)."
        else:
            text += f"\n\nThe grader shrank the failure to this small input ({tried} run)."
        candidates = [
            (m.id, reference.function(spec, m.function or "", m.line)) for m in spec.misconceptions
        ]
        if failure.kind == "mismatch":  # more evidence: every explicit edge example, in order
            collect_failures(
                outcome,
                inputs=opts.examples,
                signature=opts.signature,
                returns=opts.returns,
                tolerance=opts.tolerance,
                reference=ref,
                call=call,
            )
        passed = [
            (ex, ref(**copy.deepcopy(ex)))
            for ex in opts.examples
            if failure.kind == "mismatch" and not any(f.kwargs == ex for f in outcome.failures)
        ]
        found = matching_misconception(
            outcome, opts.returns, opts.tolerance, candidates, passed=passed
        )
        if found:
            m = next(m for m in spec.misconceptions if m.id == found)
            message = render(spec, m.message, Variant(0, {}))
            return Verdict.wrong(f"{text}\n\n{message}", misconception=found, **details)
        return Verdict.wrong(text, **details)

    # ------------------------------------------------------------------ validation
    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        from slamcourse.grading.properties import TrustedCallee

        opts: CodeOptions = spec.options
        problems: list[Problem] = []
        if variant.seed != 0:
            return problems  # Hypothesis covers the inputs; one run is enough
        for label, path, want_pass in (
            ("solution", opts.solution, True),
            ("starter", opts.starter, False),
        ):
            verdict = self.check_source(spec, read_course_file(path, spec.course_root), path.name)
            if verdict.passed != want_pass:
                problems.append(
                    problem(
                        spec,
                        spec.line,
                        f"the {label} {path.name} "
                        f"{'fails' if want_pass else 'passes'}: "
                        f"{verdict.feedback.splitlines()[0]}",
                    )
                )
        strategy = self.strategy(spec)
        for m in spec.misconceptions:
            fn = reference.function(spec, m.function or "", m.line)
            verdict = self._grade(
                spec,
                TrustedCallee(fn).call,
                strategy,
                "reference.py",
                isolation="trusted",
                use_recording=False,
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


def _load_verdict(loaded: Any, filename: str, opts: CodeOptions) -> Verdict:
    sig = f"def {opts.function}({', '.join(opts.signature)})"
    status = loaded.status
    if status == "syntax_error":
        where = f"{filename}:{loaded.line}" if loaded.line else filename
        return Verdict.unreadable(f"{where}: syntax error: {loaded.message}")
    if status == "missing_function":
        found = f" (it defines {', '.join(loaded.found)})" if loaded.found else ""
        return Verdict.unreadable(
            f"{filename} has no function {opts.function}{found}; write `{sig}:`"
        )
    if status == "not_callable":
        return Verdict.unreadable(
            f"{opts.function} in {filename} is not a function; write `{sig}:`"
        )
    if status == "signature":
        return Verdict.unreadable(
            f"{opts.function} must take {len(opts.signature)} parameters "
            f"({', '.join(opts.signature)}); {loaded.message}".rstrip("; ")
        )
    if status == "import_error":
        where = "".join(f"\n  {filename}:{f.line}: {f.text}" for f in loaded.frames[-3:])
        return Verdict.wrong(f"{filename} raised while it was loaded: {loaded.message}{where}")
    if status == "timeout":
        return Verdict(
            "timeout",
            0.0,
            f"{filename} did not finish loading in time: is there a "
            "loop at the top level of the file?",
        )
    return Verdict.wrong(f"{filename} stopped the grader's worker while loading: {loaded.message}")


def _sentence(text: str) -> str:
    text = text.strip()
    if not text:
        return ""
    return text[0].upper() + text[1:] + ("" if text.endswith((".", "!", "?")) else ".")


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
