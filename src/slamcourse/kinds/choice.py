"""The ``choice`` (one answer) and ``multi`` (several answers) kinds, with per-choice feedback.

Options whose ids are mere labels (``a``, ``b``, ``c``, … or ``1``, ``2``, ``3``, …) are shown
shuffled per variant and relabelled in the order shown: the letters a learner sees (and types)
are a deterministic function of (exercise id, variant seed), the same in the terminal, the
browser and the batch grader, and say nothing about the order the author wrote them in.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol, TypeVar

from slamcourse.answers import parse_ids
from slamcourse.course.model import ExerciseSpec, Text, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict, LineList
from slamcourse.errors import AnswerFormatError, Problem
from slamcourse.kinds.base import Kind, call_reference, course_error, problem, render
from slamcourse.verdict import Verdict, literal

LETTERS = "abcdefghijklmnopqrstuvwxyz"


def position_labels(ids: Sequence[str]) -> list[str] | None:
    """The labels ``a, b, c, …`` (or ``1, 2, 3, …``) when ``ids`` are exactly those labels in
    some order: ids that only say where the author wrote an option, which the kinds relabel in
    the order shown. None for named ids (``c1``…``c9``, ``p m u``), which are shown as
    written."""
    n = len(ids)
    for alphabet in (list(LETTERS[:n]), [str(i) for i in range(1, n + 1)]):
        if len(alphabet) == n and sorted(ids) == sorted(alphabet):
            return alphabet
    return None


class _Labelled(Protocol):
    @property
    def id(self) -> str: ...


T = TypeVar("T", bound=_Labelled)


def labelled(items: Sequence[T]) -> list[tuple[str, T]]:
    """(label, item) for ``items`` (each with an ``id``) in the order shown: relabelled
    ``a, b, c, …`` in that order when the ids are mere labels (:func:`position_labels`), else
    under their own ids."""
    ids = [item.id for item in items]
    labels = position_labels(ids)
    return list(zip(labels if labels is not None else ids, items, strict=True))


@dataclass(frozen=True)
class Choice:
    id: str
    text: str  # templates (Markdown), rendered with the variant's parameters when shown
    correct: bool
    feedback: str
    line: int
    text_line: int = 0  # where the text and the feedback start (0: at ``line``)
    feedback_line: int = 0

    def shown_text(self, spec: ExerciseSpec, variant: Variant) -> str:
        """The option's text for this variant (course text: Markdown)."""
        return render(spec, Text(self.text, self.text_line or self.line), variant)

    def shown_feedback(self, spec: ExerciseSpec, variant: Variant) -> str:
        """The option's feedback for this variant, rendered like a prompt (course text)."""
        return render(spec, Text(self.feedback, self.feedback_line or self.line), variant)


@dataclass(frozen=True)
class ChoiceOptions:
    choices: tuple[Choice, ...]  # as written
    shuffle: bool  # shown in a per-variant order (default: when the ids are mere labels)

    def ids(self) -> list[str]:
        return [c.id for c in self.choices]

    def by_id(self, cid: str) -> Choice:
        return next(c for c in self.choices if c.id == cid)


class ChoiceKind(Kind):
    """Pick exactly one option."""

    name: ClassVar[str] = "choice"
    multiple: ClassVar[bool] = False
    keys: ClassVar[dict[str, bool]] = {"choices": True, "shuffle": False}
    misconception_key: ClassVar[str | None] = None

    def reference_optional(self, raw: LineDict) -> bool:
        items = raw.get("choices")
        return isinstance(items, list) and any(
            isinstance(c, dict) and c.get("correct") is True for c in items
        )

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> ChoiceOptions:
        super().parse(spec, raw, check)
        items = check.typed(raw, "choices", list, [])
        choices: list[Choice] = []
        for i, item in enumerate(items):
            line = items.line_of(i) if isinstance(items, LineList) else raw.line
            data = check.mapping(item, line, "a choice")
            if data is None:
                continue
            check.keys(data, {"id", "text", "correct", "feedback"}, ("id", "text"), "a choice")
            cid = str(check.typed(data, "id", (str, int), f"{i}")).lower()
            if not cid.isalnum():
                check.add(line, f"choice id '{cid}' must be letters or digits (learners type it)")
            if cid in [c.id for c in choices]:
                check.add(line, f"choice id '{cid}' is used twice")
            lines = data if isinstance(data, LineDict) else None
            choices.append(
                Choice(
                    cid,
                    str(check.typed(data, "text", str, "")),
                    bool(check.typed(data, "correct", bool, False)),
                    str(check.typed(data, "feedback", str, "")),
                    line,
                    lines.text_line("text") if lines is not None else 0,
                    lines.text_line("feedback") if lines is not None else 0,
                )
            )
        if len(choices) < 2:
            check.add(raw.line_of("choices"), "give at least two choices")
        flagged = [c for c in choices if c.correct]
        if spec.reference and flagged:
            check.add(
                flagged[0].line,
                "mark correct choices either with 'correct: true' or by 'reference', not both",
            )
        if not spec.reference:
            if not self.multiple and len(flagged) != 1:
                check.add(
                    raw.line_of("choices"),
                    f"a choice exercise needs exactly one 'correct: true' (found {len(flagged)})",
                )
            if self.multiple and not flagged:
                check.add(raw.line_of("choices"), "mark at least one choice 'correct: true'")
        by_default = position_labels([c.id for c in choices]) is not None
        return ChoiceOptions(tuple(choices), bool(check.typed(raw, "shuffle", bool, by_default)))

    def expected(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        opts: ChoiceOptions = spec.options
        if not spec.reference:
            return [c.id for c in opts.choices if c.correct]
        value: Any = call_reference(spec, variant)
        ids = [str(v).lower() for v in (value if isinstance(value, list | tuple) else [value])]
        unknown = [i for i in ids if i not in opts.ids()]
        if unknown or not ids or (not self.multiple and len(ids) != 1):
            raise course_error(
                spec,
                spec.reference_line,
                f"the reference returned {value!r}; "
                f"it must return {'a list of ' if self.multiple else 'one '}"
                f"choice id(s) from {', '.join(opts.ids())}",
            )
        return ids

    def display_order(self, spec: ExerciseSpec, variant: Variant) -> list[Choice]:
        """The options in the order this variant shows them."""
        opts: ChoiceOptions = spec.options
        choices = list(opts.choices)
        if opts.shuffle:
            random.Random(f"{spec.id}:{variant.seed}:choices").shuffle(choices)
        return choices

    def shown(self, spec: ExerciseSpec, variant: Variant) -> list[tuple[str, Choice]]:
        """(label, option) in the order shown: the letters ``a, b, c, …`` in that order when
        the authored ids are mere labels, else the authored ids. What a face shows, what a
        learner types and what :meth:`check` reads."""
        return labelled(self.display_order(spec, variant))

    def labels(self, spec: ExerciseSpec, variant: Variant) -> dict[str, str]:
        """Authored id → the label this variant shows it under."""
        return {c.id: label for label, c in self.shown(spec, variant)}

    def shown_answer(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        """The right answer as this variant's learner types it (labels, in the order shown).
        :meth:`expected` is the same in authored ids (what an explanation template sees)."""
        right = set(self.expected(spec, variant))
        return [label for label, c in self.shown(spec, variant) if c.id in right]

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        options = [
            {"id": label, "text": c.shown_text(spec, variant)}
            for label, c in self.shown(spec, variant)
        ]
        return {"type": self.name, "options": options}

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        ids = ", ".join(label for label, _ in self.shown(spec, variant))
        if self.multiple:
            return (
                f"Answer with every option that applies, e.g. `{self.example(spec, variant)}` "
                f"(options: {ids})."
            )
        return f"Answer with one option: {ids}."

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        if not self.multiple:
            return []
        ids = [label for label, _ in self.shown(spec, variant)]
        return [f"{ids[0]} {ids[-1]}", ids[0], f"{ids[0]} {ids[1]}", ids[-1], " ".join(ids)]

    def _read(self, spec: ExerciseSpec, variant: Variant, answer: str) -> list[tuple[str, Choice]]:
        """The (label, option) pairs picked, each once, in the order given."""
        by_label = dict(self.shown(spec, variant))
        picked = parse_ids(answer)
        unknown = [p for p in picked if p not in by_label]
        if unknown:
            raise AnswerFormatError(
                f"there is no option '{unknown[0]}'; choose from {', '.join(by_label)}"
            )
        return [(p, by_label[p]) for p in dict.fromkeys(picked)]

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        try:
            picked = self._read(spec, variant, answer)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        if len(picked) != 1:
            return Verdict.unreadable(f"choose exactly one option (you gave {len(picked)})")
        label, choice = picked[0]
        said = choice.shown_feedback(spec, variant)
        if [choice.id] == self.expected(spec, variant):  # the face says "correct": not twice
            return Verdict.ok(said or "That is the right option.")
        return Verdict.wrong(f"Not quite. {said}".strip(), picked=[label])

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        right = self.shown_answer(spec, variant)
        problems = []
        if not self.check(spec, variant, " ".join(right)).passed:
            problems.append(problem(spec, spec.line, "the correct choice is not accepted"))
        for label, c in self.shown(spec, variant):
            if label not in right and self.check(spec, variant, label).passed:
                problems.append(problem(spec, c.line, f"wrong choice '{c.id}' is accepted"))
        return problems


class MultiKind(ChoiceKind):
    """Pick every option that applies; partial credit (right − wrong picks) / number right."""

    name: ClassVar[str] = "multi"
    multiple: ClassVar[bool] = True

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        try:
            picked = self._read(spec, variant, answer)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        right = set(self.expected(spec, variant))
        wrong_picks = [(label, c) for label, c in picked if c.id not in right]
        hits = len([c for _, c in picked if c.id in right])
        score = max(0.0, (hits - len(wrong_picks)) / len(right))
        if not wrong_picks and hits == len(right):
            return Verdict.ok("Exactly the right options.")
        parts = [f"Not quite ({hits} of {len(right)} right options picked)."]
        for label, c in wrong_picks:  # one paragraph each; `1)` is no list item
            parts.append(
                f"{literal(label + ')')} does not apply. {c.shown_feedback(spec, variant)}".strip()
            )
        missing = len(right) - hits
        if missing:
            parts.append(
                f"{missing} option{'s' if missing > 1 else ''} that appl"
                f"{'y' if missing > 1 else 'ies'} {'are' if missing > 1 else 'is'} missing."
            )
        return Verdict.wrong("\n\n".join(parts), score=score, picked=[label for label, _ in picked])

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        right = self.shown_answer(spec, variant)
        problems = []
        if not self.check(spec, variant, " ".join(right)).passed:
            problems.append(problem(spec, spec.line, "the correct set of choices is not accepted"))
        for label, c in self.shown(spec, variant):
            if label not in right and self.check(spec, variant, " ".join([*right, label])).passed:
                problems.append(problem(spec, c.line, f"adding wrong choice '{c.id}' is accepted"))
        return problems
