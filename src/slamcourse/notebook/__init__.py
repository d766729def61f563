"""The notebook face: the course in Jupyter, over the same engine as the terminal and browser.

In a notebook::

    %load_ext slamcourse.notebook
    from slamcourse.notebook import check, explain, give_up, hint, progress, show

    show("se2/between")                 # the prompt of your own variant, math typeset
    check("se2/compose-value", "[1.2, 0.4, 0.3]")
    check("se2/compose-value", np.array([1.2, 0.4, 0.3]))   # a value is written out in full

and a code exercise is answered by a cell that starts with the cell magic::

    %%slamcourse check se2/between
    import math
    def between(a, b):
        ...

(or ``check("se2/between", between)``: a function defined in the notebook, graded by its
source). Every call returns an object that displays as HTML in a notebook and as text in a
console; every rule (which variant is yours, what counts as an attempt, when the explanation
unlocks) is the engine's, and progress goes to the same store as ``slamcourse`` in a terminal
and ``slamcourse serve`` (``$SLAMCOURSE_HOME``). A learner's mistake (an unknown id, an
explanation asked for too early) is displayed as a notice, never raised.

This module imports IPython only in :func:`load_ipython_extension`; nothing of the core
imports this package.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

from slamcourse.errors import SlamcourseError
from slamcourse.notebook.cells import CHECK, answer_text, parse_magic_args

if TYPE_CHECKING:
    from collections.abc import Callable

    from slamcourse.engine import Engine, Prompt
    from slamcourse.notebook.views import (
        ExerciseView,
        ExplanationView,
        HintView,
        Notice,
        ProgressView,
        ResultView,
    )

__all__ = [
    "check",
    "close",
    "explain",
    "give_up",
    "hint",
    "load_ipython_extension",
    "progress",
    "show",
    "use",
]

_lock = threading.Lock()
_engine: Engine | None = None
_identity: dict[str, Any] | None = None


# ------------------------------------------------------------------------------ the session


def engine() -> Engine:
    """The engine of this kernel: opened on first use from the environment (the same course,
    progress store and workspace as ``slamcourse`` in a terminal), kept until :func:`close`."""
    global _engine
    with _lock:
        if _engine is None:
            from slamcourse.engine import Engine

            _engine = Engine.open()
        return _engine


def use(new: Engine | None) -> None:
    """Make ``new`` this kernel's engine (another course or home); None closes the current."""
    global _engine, _identity
    with _lock:
        old, _engine, _identity = _engine, new, None
    if old is not None and old is not new:
        old.close()


def close() -> None:
    """Close this kernel's engine (the next call opens it again)."""
    use(None)


def identity() -> dict[str, Any]:
    """Who is learning and which course: the output metadata the batch grader reads from a
    handed-in notebook (the same fields as a submission's manifest)."""
    global _identity
    eng = engine()
    if _identity is None:
        from slamcourse import __version__
        from slamcourse.batch.submission import course_hash, learner_id
        from slamcourse.course.locate import bundled_course_root, course_root

        root = course_root(eng.settings.course)
        seed = eng._store().learner_seed
        _identity = {
            "learner": {"id": learner_id(seed), "name": None, "seed": seed},
            "course": {
                "version": __version__ if root == bundled_course_root() else "custom",
                "hash": course_hash(root),
            },
            "engine": __version__,
        }
    return dict(_identity)


def _meta(**more: Any) -> dict[str, Any]:
    return {**identity(), **{k: v for k, v in more.items() if v is not None}}


def _picture(eng: Engine, prompt: Prompt) -> str | None:
    """The exercise's picture of this variant; one that shows the answer only once the
    exercise is solved or given up (the engine's state)."""
    from slamcourse.plots.registry import plot_for

    spec = eng.exercise(prompt.exercise_id)
    solved = eng.state(prompt.exercise_id).status != "pending"
    return plot_for(prompt.exercise_id, spec.tags, dict(prompt.variant.params), solved=solved)


def _notice(exc: SlamcourseError) -> Notice:
    from slamcourse.notebook.views import Notice

    try:
        meta = _meta()
    except SlamcourseError:
        meta = {}
    return Notice(str(exc), meta=meta)


# ------------------------------------------------------------------------------ the functions


def show(exercise_id: str, *, canonical: bool = False) -> ExerciseView | Notice:
    """Pose an exercise: your own variant (``canonical``: the lesson's own numbers, practice)."""
    from slamcourse.engine import STATUS_MARK, STATUS_WORD
    from slamcourse.notebook.views import ExerciseView

    try:
        eng = engine()
        prompt = eng.pose(exercise_id, canonical=canonical)
        _ = prompt.form
        return ExerciseView(
            prompt,
            _picture(eng, prompt),
            STATUS_MARK[prompt.status],
            STATUS_WORD[prompt.status],
            meta=_meta(exercise=exercise_id, variant=prompt.variant.seed),
        )
    except SlamcourseError as exc:
        return _notice(exc)


def check(exercise_id: str, answer: Any, *, canonical: bool = False) -> ResultView | Notice:
    """Grade an answer. A text exercise takes the answer as text (``"7/5"``, ``"[1, 2]"``)
    or a value (a number, a list, a numpy array: written out in full precision); a code
    exercise takes the function itself (graded by its source, with the imports and helpers
    of this notebook it uses) or its source as text."""
    try:
        eng = engine()
        spec = eng.exercise(exercise_id)
        if spec.kind == "code":
            source = answer if isinstance(answer, str) else function_source(answer, spec)
            return _check_code(eng, exercise_id, source)
        text = answer_text(answer)
        if text is None:
            raise _Unanswered(
                f"No answer yet: write it as the second argument, e.g. "
                f'`{CHECK}("{exercise_id}", "0.25")`.'
            )
        result = eng.submit(exercise_id, text, canonical=canonical)
        return _result_view(eng, result, answer=text)
    except SlamcourseError as exc:
        return _notice(exc)


class _Unanswered(SlamcourseError):
    """``check`` was given no answer (None, ``...``)."""


def _check_code(
    eng: Engine, exercise_id: str, source: str, *, note: str | None = None
) -> ResultView:
    eng.start_workers()  # a kernel checks again and again: forked from one warm zygote
    result = eng.submit_code(exercise_id, source=source)
    return _result_view(eng, result, source=source, note=note)


def _result_view(
    eng: Engine,
    result: Any,
    *,
    answer: str | None = None,
    source: str | None = None,
    note: str | None = None,
) -> ResultView:
    from slamcourse.notebook.views import ResultView

    picture = None
    if result.verdict.passed and not result.practice:
        picture = _picture(eng, eng.pose(result.exercise_id))
    meta = _meta(
        exercise=result.exercise_id,
        variant=result.variant,
        answer=answer,
        source=source,  # what was graded: a handed-in notebook is graded on the same
        status=result.verdict.status,
    )
    return ResultView(result, picture, note, meta=meta)


def hint(exercise_id: str) -> HintView | Notice:
    """Reveal the next hint of your variant (recorded, as in the terminal and browser)."""
    from slamcourse.notebook.views import HintView

    try:
        return HintView(exercise_id, engine().hint(exercise_id), meta=_meta(exercise=exercise_id))
    except SlamcourseError as exc:
        return _notice(exc)


def explain(exercise_id: str) -> ExplanationView | Notice:
    """The worked explanation of your variant, once the exercise is solved or given up."""
    from slamcourse.notebook.views import ExplanationView

    try:
        eng = engine()
        text = eng.explanation(exercise_id)
        picture = _picture(eng, eng.pose(exercise_id))
        return ExplanationView(exercise_id, text, picture, meta=_meta(exercise=exercise_id))
    except SlamcourseError as exc:
        return _notice(exc)


def give_up(exercise_id: str) -> ExplanationView | Notice:
    """Give up on an exercise (unless solved) and show its explanation."""
    from slamcourse.notebook.views import ExplanationView

    try:
        eng = engine()
        text = eng.give_up(exercise_id)
        picture = _picture(eng, eng.pose(exercise_id))
        return ExplanationView(exercise_id, text, picture, meta=_meta(exercise=exercise_id))
    except SlamcourseError as exc:
        return _notice(exc)


def progress(chapter: str | None = None) -> ProgressView | Notice:
    """Solved per chapter, or (``chapter``) each exercise of one chapter with its status."""
    from slamcourse.batch.submission import learner_id
    from slamcourse.engine import STATUS_MARK, STATUS_WORD
    from slamcourse.errors import UsageError
    from slamcourse.notebook.views import ProgressView

    try:
        eng = engine()
        summary = eng.summary()
        if chapter is not None and chapter not in {ch["id"] for ch in summary}:
            ids = ", ".join(ch["id"] for ch in summary)
            raise UsageError(f"no chapter {chapter!r} in this course (chapters: {ids})")
        who = learner_id(eng._store().learner_seed)
        return ProgressView(summary, STATUS_MARK, STATUS_WORD, who, chapter, meta=_meta())
    except SlamcourseError as exc:
        return _notice(exc)


# ------------------------------------------------------------------------------ functions


def function_source(fn: Any, spec: Any) -> str:
    """The source a function defined in a notebook is graded by: the imports and helpers it
    uses (modules, functions and plain constants of its notebook), then the function itself,
    bound to the name the exercise asks for."""
    import inspect
    import textwrap
    import types

    from slamcourse.errors import UsageError

    name = spec.options.function
    if not isinstance(fn, types.FunctionType):
        raise UsageError(
            f"{spec.id} is a code exercise: pass the function `{name}` itself, or its "
            f"source as text, or answer in a cell that starts with "
            f"`%%slamcourse check {spec.id}`"
        )
    if fn.__name__ == "<lambda>":
        raise UsageError(f"define `{name}` with `def` (a lambda has no source of its own)")
    parts: list[str] = []
    seen: set[str] = set()

    def add(f: types.FunctionType) -> None:
        try:
            body = textwrap.dedent(inspect.getsource(f))
        except (OSError, TypeError) as exc:
            raise UsageError(
                f"the source of `{f.__name__}` cannot be found ({exc}); answer in a cell that "
                f"starts with `%%slamcourse check {spec.id}` instead"
            ) from None
        for used in sorted(_global_names(f.__code__)):
            if used in seen or used not in f.__globals__:
                continue
            seen.add(used)
            value = f.__globals__[used]
            if isinstance(value, types.ModuleType):
                mod = value.__name__
                parts.append(f"import {mod}" if mod == used else f"import {mod} as {used}")
            elif isinstance(value, types.FunctionType) and value.__module__ == f.__module__:
                if value is not fn:
                    add(value)
            elif callable(value) and getattr(value, "__module__", None):
                module = value.__module__
                if (
                    module not in ("__main__", "builtins")
                    and getattr(value, "__name__", "") == used
                ):
                    parts.append(f"from {module} import {used}")
            elif isinstance(value, (int, float, str, bool, tuple)) and _literal(value):
                parts.append(f"{used} = {value!r}")
        parts.append(body)

    seen.add(fn.__name__)
    add(fn)
    if fn.__name__ != name:
        parts.append(f"{name} = {fn.__name__}")
    return "\n\n".join(parts) + "\n"


def _literal(value: Any) -> bool:
    import ast

    try:
        ast.literal_eval(repr(value))
    except (ValueError, SyntaxError, TypeError):
        return False
    return True


def _global_names(code: Any) -> set[str]:
    names = set(code.co_names)
    for const in code.co_consts:
        if hasattr(const, "co_names"):
            names |= _global_names(const)
    return names


# ------------------------------------------------------------------------------ IPython


def _cell_magic(shell: Any) -> Callable[[str, str], Any]:
    def slamcourse(line: str, cell: str) -> Any:
        """%%slamcourse check ID: grade this cell's source as the code exercise ID (in the
        sandbox; progress recorded), then define it in the notebook as well."""
        parsed = parse_magic_args(line)
        if parsed is None:
            from slamcourse.errors import UsageError

            return _notice(UsageError(f"write `%%slamcourse check ID` (got `{line.strip()}`)"))
        exercise_id = parsed[1]
        try:
            eng = engine()
            spec = eng.exercise(exercise_id)
            if spec.kind != "code":
                from slamcourse.errors import UsageError

                raise UsageError(
                    f"{exercise_id} is a {spec.kind} exercise: answer it with "
                    f'`{CHECK}("{exercise_id}", "your answer")`'
                )
            view = _check_code(eng, exercise_id, cell)
        except SlamcourseError as exc:
            return _notice(exc)
        if view.status in ("passed", "failed"):  # it compiled and imported: define it here
            try:
                exec(compile(cell, f"<{exercise_id}>", "exec"), shell.user_ns)
            except Exception as exc:
                view.note = f"Defining it in this notebook raised {type(exc).__name__}: {exc}"
        return view

    return slamcourse


def load_ipython_extension(ipython: Any) -> None:
    """``%load_ext slamcourse.notebook``: registers the ``%%slamcourse`` cell magic."""
    ipython.register_magic_function(
        _cell_magic(ipython), magic_kind="cell", magic_name="slamcourse"
    )


def unload_ipython_extension(ipython: Any) -> None:
    close()
