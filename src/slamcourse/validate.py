"""``slamcourse validate``: prove every exercise of a course sound, on many variants.

For code exercises it also grades, through the real sandbox, the solution, the starter, every
mutant (a plausible wrong implementation, which must fail) and every correct variant (another
method, which must pass); requires at least ``min_mutants`` and ``min_variants`` of them; and
checks the recording of test inputs shipped with the course (``record=True`` rewrites it).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from slamcourse.course import templates, variants
from slamcourse.course.loader import Course, load_course
from slamcourse.course.model import Chapter, ExerciseSpec, Text
from slamcourse.errors import CourseError, GraderError, Problem, UsageError, relpath
from slamcourse.kinds import get_kind

MIN_MUTANTS = 8
MIN_VARIANTS = 3


@dataclass
class Report:
    """What validation found: problems (``path:line: message``) and what was covered."""

    problems: list[Problem] = field(default_factory=list)
    exercises: int = 0
    variants: int = 0
    warnings: list[Problem] = field(default_factory=list)  # shown, but never fail validation

    @property
    def ok(self) -> bool:
        return not self.problems


def validate_course(
    root: Path,
    *,
    variants_per_exercise: int = 25,
    progress: Callable[[str], None] | None = None,
    min_mutants: int | None = None,
    min_variants: int | None = None,
    record: bool = False,
    only: list[str] | None = None,
) -> Report:
    """Load every chapter and exercise of the course at ``root`` and check each one (``only``:
    just these exercise ids, which must exist).

    ``min_mutants``/``min_variants`` default to :data:`MIN_MUTANTS`/:data:`MIN_VARIANTS`;
    ``record`` (re)writes each code exercise's shipped recording before checking it."""
    course = load_course(root)
    report = Report(list(course.problems))
    placed = set(course.exercise_ids)
    paths = sorted((root / "exercises").glob("*/*.yaml"))
    if only is not None:
        known = {f"{p.parent.name}/{p.stem}" for p in paths}
        unknown = [ex for ex in only if ex not in known]
        if unknown:
            raise UsageError(
                f"no exercise {', '.join(unknown)} in the course at {root} "
                "(ids look like se2/between; `slamcourse list` shows them)"
            )
        paths = [p for p in paths if f"{p.parent.name}/{p.stem}" in only]
    for path in paths:
        ex_id = f"{path.parent.name}/{path.stem}"
        if ex_id not in placed:
            report.problems.append(
                Problem(
                    relpath(path, root),
                    1,
                    f"exercise '{ex_id}' is not "
                    "placed in any chapter; add a ```{exercise} "
                    f"{ex_id} block to its chapter",
                )
            )
            continue
        if progress:
            progress(ex_id)
        report.problems.extend(
            validate_exercise(
                course,
                ex_id,
                variants_per_exercise,
                report,
                min_mutants=min_mutants,
                min_variants=min_variants,
                record=record,
            )
        )
    chapters = course.chapters
    if only is not None:
        chapters = [ch for ch in chapters if set(ch.exercises) & set(only)]
    report.problems.extend(figure_drawings(chapters, root))
    specs = []
    for ex_id in course.exercise_ids if only is None else only:
        try:
            specs.append(course.exercise(ex_id))
        except CourseError:
            continue  # reported above
    for spec in specs:
        report.warnings.extend(letters_named(spec))
    if only is None:  # a habit of the whole course, not of one exercise
        report.warnings.extend(key_bias(specs))
    return report


# ------------------------------------------------------------------------------ figures


def svg_problem(svg: object) -> str | None:
    """Why ``svg`` is not an accessible SVG picture (None when it is): well-formed XML, an
    ``<svg role="img">`` root whose ``<title>`` and ``<desc>`` hold text."""
    import xml.etree.ElementTree as ET

    if not isinstance(svg, str):
        return f"returned {type(svg).__name__}, not SVG text"
    try:
        root = ET.fromstring(svg)
    except ET.ParseError as exc:
        return f"returned SVG that is not well-formed XML ({exc})"
    ns = "{http://www.w3.org/2000/svg}"
    if root.tag != f"{ns}svg":
        return f"returned <{root.tag.removeprefix(ns)}>, not an <svg> element"
    if root.get("role") != "img":
        return 'returned an <svg> without role="img"'
    for part in ("title", "desc"):
        found = root.find(f"{ns}{part}")
        if found is None or not (found.text or "").strip():
            return f"returned an <svg> without a <{part}> (its text alternative)"
    return None


def figure_drawings(chapters: list[Chapter], root: Path) -> list[Problem]:
    """Draw every figure the chapters place, once: one that raises or returns something that
    is not an accessible SVG is a problem at its block's line (an unknown id is reported by
    the loader)."""
    from slamcourse.plots.registry import FIGURES

    problems = []
    for chapter in chapters:
        for fig in chapter.figures:
            draw = FIGURES.get(fig.id)
            if draw is None:
                continue
            try:
                why = svg_problem(draw())
            except Exception as exc:  # a drawing bug must not stop validation
                why = f"raised {type(exc).__name__}: {exc}"
            if why:
                problems.append(
                    Problem(
                        relpath(chapter.path, root),
                        fig.line,
                        f"figure '{fig.id}' {why}; fix its drawing function in "
                        "src/slamcourse/plots/",
                    )
                )
    return problems


# ------------------------------------------------------------------------------ key bias

BIAS_MIN = 3  # fewer exercises with the same habit say nothing
BIAS_SHARE = 0.5  # a habit: at least half of the fixed keys, and twice what chance gives
ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth")


def key_bias(specs: list[ExerciseSpec]) -> list[Problem]:
    """Warnings (never problems) where the fixed keys of the course's choice exercises follow
    a habit a learner could learn: the correct option usually written at the same place, the
    correct option usually the longest, a multi exercise's right options usually the first
    ones written. Each warning is at the correct option's line of an exercise that follows
    the habit. Keys computed by a reference vary with the variant and are not counted."""
    single = [s for s in specs if s.kind == "choice" and not s.reference]
    multi = [s for s in specs if s.kind == "multi" and not s.reference]
    warnings: list[Problem] = []

    # where the key is written: the same place from the start (or from the end) in most
    at: dict[tuple[str, int], list[ExerciseSpec]] = {}
    for spec in single:
        ids = spec.options.ids()
        i = next(n for n, c in enumerate(spec.options.choices) if c.correct)
        at.setdefault(("start", i), []).append(spec)
        at.setdefault(("end", len(ids) - 1 - i), []).append(spec)
    if at:
        (side, place), habit = max(at.items(), key=lambda kv: (len(kv[1]), kv[0][0] == "start"))
        if _is_habit(habit, single, lambda s: 1 / len(s.options.choices)):
            if side == "start":
                where = ORDINALS[place] if place < len(ORDINALS) else f"number {place + 1}"
            else:
                where = "last" if place == 0 else f"{ORDINALS[place]} from the end"
            for spec in habit:
                key = next(c for c in spec.options.choices if c.correct)
                leak = (
                    "this exercise has `shuffle: false`, so its learners see it there: vary it"
                    if not spec.options.shuffle
                    else "learners see the options shuffled and relabelled per variant, so "
                    "this does not give the answer away, but vary where you write the key"
                )
                warnings.append(
                    _warning(
                        spec,
                        key.line,
                        f"the correct choice '{key.id}' is written {where} of the options, as "
                        f"in {len(habit)} of {len(single)} single-choice exercises with a fixed "
                        f"key; {leak}",
                    )
                )

    # the key is the longest option
    longest = [s for s in single if _key_is_longest(s)]
    if _is_habit(longest, single, lambda s: 1 / len(s.options.choices)):
        for spec in longest:
            key = next(c for c in spec.options.choices if c.correct)
            warnings.append(
                _warning(
                    spec,
                    key.line,
                    f"the correct choice '{key.id}' is the longest option, as in "
                    f"{len(longest)} of {len(single)} single-choice exercises with a fixed key: "
                    "shuffling hides its position but not its length, so learners can guess "
                    "it; shorten it or lengthen the other options",
                )
            )

    # a multi exercise's right options are the first ones written
    first = [s for s in multi if _keys_come_first(s)]
    if _is_habit(first, multi, lambda s: 1 / _subsets(s)):
        for spec in first:
            key = [c for c in spec.options.choices if c.correct]
            warnings.append(
                _warning(
                    spec,
                    key[-1].line,
                    f"the right options ({', '.join(c.id for c in key)}) are the first "
                    f"{len(key)} written, as in {len(first)} of {len(multi)} multi exercises "
                    "with a fixed key; learners see the options shuffled and relabelled per "
                    "variant, so this does not give the answer away, but vary where you write "
                    "them",
                )
            )
    return warnings


_LETTER_RUN = re.compile(r"\b[a-z](?:(?:, | and | or |, and |, or )[a-z]\b)+")


def letters_named(spec: ExerciseSpec) -> list[Problem]:
    """Warnings where the prose of a relabelled choice or order exercise names options by the
    letters they were written with ("The order is a, b, c, d"): each learner sees them
    shuffled and relabelled, so those letters are not the ones on their screen."""
    if spec.kind == "order":
        ids = [it.id for it in spec.options.items]
        texts = list(spec.options.feedback.values())
    elif spec.kind in ("choice", "multi") and spec.options.shuffle:
        ids = spec.options.ids()
        texts = [c.feedback for c in spec.options.choices]
    else:
        return []
    if sorted(ids) != [chr(ord("a") + i) for i in range(len(ids))]:
        return []  # named ids are shown as written
    found = []
    for where, text, line in [
        ("prompt", spec.prompt.source, spec.prompt.line),
        ("explanation", spec.explanation.source, spec.explanation.line),
        *[("hint", h.source, h.line) for h in spec.hints],
        *[("feedback", t, None) for t in texts],
    ]:
        prose = re.sub(r"\$[^$]*\$", " ", text)  # not the letters of formulas
        for run in _LETTER_RUN.findall(prose):
            if set(re.findall(r"\b[a-z]\b", run)) <= set(ids):
                found.append(
                    _warning(
                        spec,
                        line if line is not None else spec.line,
                        f"the {where} names options by the letters they are written with "
                        f"('{run}'), but each learner sees them shuffled under other "
                        "letters; name them by their text",
                    )
                )
                break
    return found


def _is_habit(
    habit: list[ExerciseSpec], among: list[ExerciseSpec], chance: Callable[[ExerciseSpec], float]
) -> bool:
    if len(habit) < BIAS_MIN:
        return False
    expected = sum(chance(s) for s in among)  # how many follow it by chance
    return len(habit) >= max(BIAS_SHARE * len(among), 2 * expected)


def _key_is_longest(spec: ExerciseSpec) -> bool:
    key = next(c for c in spec.options.choices if c.correct)
    return all(len(key.text) > len(c.text) for c in spec.options.choices if c is not key)


def _keys_come_first(spec: ExerciseSpec) -> bool:
    flags = [c.correct for c in spec.options.choices]
    k = sum(flags)
    return k < len(flags) and all(flags[:k])


def _subsets(spec: ExerciseSpec) -> int:
    import math

    choices = spec.options.choices
    return math.comb(len(choices), sum(c.correct for c in choices))


def _warning(spec: ExerciseSpec, line: int | None, message: str) -> Problem:
    return Problem(relpath(spec.path, spec.course_root), line, f"warning: {message}")


def validate_exercise(
    course: Course,
    exercise_id: str,
    count: int,
    report: Report | None = None,
    *,
    min_mutants: int | None = None,
    min_variants: int | None = None,
    record: bool = False,
) -> list[Problem]:
    """Problems of one exercise over the canonical variant and ``count`` random ones."""
    try:
        spec = course.exercise(exercise_id)
    except CourseError as exc:
        return exc.problems
    if report is not None:
        report.exercises += 1
    kind = get_kind(spec.kind)
    before: list[Problem] = []
    if spec.kind == "code":
        try:
            before = _code_files(
                spec,
                MIN_MUTANTS if min_mutants is None else min_mutants,
                MIN_VARIANTS if min_variants is None else min_variants,
                record,
            )
        except CourseError as exc:
            before = exc.problems
        except GraderError as exc:
            before = [Problem(relpath(spec.path, spec.course_root), spec.line, str(exc))]
    seeds = [0] + (list(range(1, count + 1)) if spec.has_variants else [])
    first: dict[tuple[str, int | None], Problem] = {}  # one report per place...
    seen_in: dict[tuple[str, int | None], int] = {}  # ...with the number of variants it hit
    checked = 0
    for seed in seeds:
        try:
            variant = variants.variant(spec, seed)
            found = template_problems(spec, variant.params, kind.expected(spec, variant))
            if not found:  # the kinds render these same texts while they check
                found = kind.self_test(spec, variant) + kind.example_problems(spec, variant)
        except CourseError as exc:
            found = exc.problems
        except GraderError as exc:  # e.g. the reference fails on an input the strategy drew
            found = [Problem(relpath(spec.path, spec.course_root), spec.line, str(exc))]
        checked += 1
        if report is not None:
            report.variants += 1
        for p in found:
            key = (p.path, p.line)
            first.setdefault(key, p)
            seen_in[key] = seen_in.get(key, 0) + 1
    problems = list(before)
    for key, p in first.items():
        times = seen_in[key]
        suffix = f" (in {times} of {checked} variants checked)" if checked > 1 and times > 1 else ""
        problems.append(Problem(p.path, p.line, p.message + suffix))
    return problems


def _code_files(
    spec: ExerciseSpec, min_mutants: int, min_variants: int, record: bool
) -> list[Problem]:
    """Enough mutants and correct variants; a shipped recording that is current (or written
    now, with ``record``)."""
    from slamcourse.grading import replay
    from slamcourse.grading.properties import exercise_seed
    from slamcourse.kinds.code import submission_files

    problems = []
    where = relpath(spec.path, spec.course_root)
    mutants, correct = submission_files(spec)
    folder = relpath(spec.path.parent, spec.course_root)
    for found, wanted, name, what in (
        (len(mutants), min_mutants, "mutants", "plausible wrong implementations"),
        (len(correct), min_variants, "variants", "correct implementations by other methods"),
    ):
        if found < wanted:
            problems.append(
                Problem(
                    where,
                    spec.line,
                    f"{found} {name} in {folder}/{name}/{spec.path.stem}/, at least {wanted} "
                    f"needed: add {what} there (see docs/authoring.md, 'Mutants and variants')",
                )
            )
    seed = exercise_seed(spec.id)
    if record:
        replay.write_shipped(spec, seed, record_inputs(spec))
        return problems
    state = replay.shipped_state(spec, seed)
    shipped = relpath(replay.shipped_path(spec), spec.course_root)
    fix = "; run `slamcourse validate --record` to write it"
    if state == "missing":
        problems.append(
            Problem(
                where,
                spec.line,
                f"no recording of test inputs ({shipped}), so a learner's first check runs "
                f"Hypothesis{fix}",
            )
        )
    elif state != "ok":
        problems.append(
            Problem(
                shipped,
                1,
                (
                    "this recording is stale (it was drawn for another version of the "
                    "exercise, its reference.py, the grader or Hypothesis)"
                    if state == "stale"
                    else "this recording is unreadable"
                )
                + f" and is ignored{fix}",
            )
        )
    return problems


def record_inputs(spec: ExerciseSpec) -> list[dict[str, object]]:
    """The inputs a learner's passing check draws (explicit examples first), without calling
    anything; the reference must be defined on every one of them."""
    from slamcourse.course import reference
    from slamcourse.grading.properties import exercise_seed
    from slamcourse.grading.testset import draw

    inputs = draw(spec, exercise_seed(spec.id), examples=spec.options.examples)
    ref = reference.function(spec, spec.reference or "", spec.reference_line)
    for kwargs in inputs:
        try:
            ref(**kwargs)
        except Exception as exc:
            raise GraderError(
                f"cannot record test inputs: the reference fails on {kwargs} "
                f"({type(exc).__name__}: {exc})"
            ) from exc
    return inputs


def course_texts(
    spec: ExerciseSpec, params: dict[str, object], answer: object
) -> list[tuple[str, Text, dict[str, object]]]:
    """Every template of an exercise a learner may see, with what it is rendered with: the
    prompt, the hints, the explanation (which also sees ``answer``), the misconceptions'
    messages, and a choice's options and their feedback or an order's steps and messages."""
    texts: list[tuple[str, Text, dict[str, object]]] = [
        ("prompt", spec.prompt, dict(params)),
        *[("hint", hint, dict(params)) for hint in spec.hints],
        ("explanation", spec.explanation, {**params, "answer": answer}),
    ]
    # a code exercise's message is shown for any input, so it sees no parameters
    message_params = {} if spec.kind == "code" else dict(params)
    texts += [("message", m.message, message_params) for m in spec.misconceptions]
    if spec.kind in ("choice", "multi"):
        for c in spec.options.choices:
            texts.append(("option", Text(c.text, c.text_line or c.line), dict(params)))
            if c.feedback:
                line = c.feedback_line or c.line
                texts.append(("option feedback", Text(c.feedback, line), dict(params)))
    elif spec.kind == "order":
        for item in spec.options.items:
            texts.append(("step", Text(item.text, item.line), dict(params)))
        for iid, message in spec.options.feedback.items():
            line = spec.options.feedback_lines.get(iid, spec.line)
            texts.append(("step feedback", Text(message, line), dict(params)))
    return texts


_LEFT_OVER = re.compile(r"\{\{|\{%")


def template_problems(
    spec: ExerciseSpec, params: dict[str, object], answer: object
) -> list[Problem]:
    """Render every template of the exercise (:func:`course_texts`) with this variant's
    parameters: a template that fails, or whose output still holds ``{{`` or ``{%`` (a tag
    that was never rendered), is a problem at its line."""
    found: list[Problem] = []
    for what, text, context in course_texts(spec, params, answer):
        where = f"template error in the {what}"
        try:
            out = templates.render(spec, text, context)
        except CourseError as exc:
            found += [
                Problem(p.path, p.line, p.message.replace("template error", where, 1))
                for p in exc.problems
            ]
            continue
        left = _LEFT_OVER.search(out)
        if left:
            found.append(
                Problem(
                    relpath(spec.path, spec.course_root),
                    text.line,
                    f"the rendered {what} still holds '{left.group(0)}' "
                    f"(…{out[max(0, left.start() - 20) : left.end() + 20]}…): a template "
                    "tag that is not rendered; check its braces",
                )
            )
    return found
