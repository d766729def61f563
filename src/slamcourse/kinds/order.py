"""The ``order`` kind: put steps in order; partial credit by the longest correctly ordered run.

Items are shown shuffled per variant; items whose ids are mere labels (``a``, ``b``, ``c``, …
or ``1``, ``2``, ``3``, …, written in the correct order) are relabelled in the order shown, so
the letters a learner sees and types never spell the answer (see ``kinds/choice.py``).
"""

from __future__ import annotations

import bisect
import random
from dataclasses import dataclass, field
from typing import Any, ClassVar

from slamcourse.answers import parse_ids
from slamcourse.course.model import ExerciseSpec, Text, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict, LineList
from slamcourse.errors import AnswerFormatError, Problem
from slamcourse.kinds.base import Kind, problem, render
from slamcourse.kinds.choice import labelled
from slamcourse.verdict import Verdict


@dataclass(frozen=True)
class Item:
    id: str
    text: str  # a template (Markdown), rendered with the variant's parameters when shown
    line: int


@dataclass(frozen=True)
class OrderOptions:
    items: tuple[Item, ...]  # in the correct order
    feedback: dict[str, str]  # item id -> a template (Markdown)
    feedback_lines: dict[str, int] = field(default_factory=dict)  # item id -> its line

    def item_text(self, spec: ExerciseSpec, variant: Variant, item: Item) -> str:
        """An item's text for this variant (course text: Markdown)."""
        return render(spec, Text(item.text, item.line), variant)

    def item_feedback(self, spec: ExerciseSpec, variant: Variant, item_id: str) -> str:
        """The message for an item out of place, rendered like a prompt (course text)."""
        line = self.feedback_lines.get(item_id, spec.line)
        return render(spec, Text(self.feedback[item_id], line), variant)


def longest_ordered(positions: list[int]) -> list[int]:
    """Indices (into ``positions``) of one longest strictly increasing subsequence."""
    tails: list[int] = []  # tails[k]: smallest tail value of an increasing run of length k+1
    tail_at: list[int] = []  # index in positions of that tail
    parent = [-1] * len(positions)
    for i, value in enumerate(positions):
        k = bisect.bisect_left(tails, value)
        if k == len(tails):
            tails.append(value)
            tail_at.append(i)
        else:
            tails[k] = value
            tail_at[k] = i
        parent[i] = tail_at[k - 1] if k else -1
    run: list[int] = []
    i = tail_at[-1] if tail_at else -1
    while i != -1:
        run.append(i)
        i = parent[i]
    return run[::-1]


class OrderKind(Kind):
    """Order the items; ``items`` are written in the correct order and shown shuffled."""

    name: ClassVar[str] = "order"
    keys: ClassVar[dict[str, bool]] = {"items": True, "feedback": False}
    reference_required: ClassVar[bool] = False
    misconception_key: ClassVar[str | None] = None

    def parse(self, spec: ExerciseSpec, raw: LineDict, check: Checker) -> OrderOptions:
        super().parse(spec, raw, check)
        items_raw = check.typed(raw, "items", list, [])
        items: list[Item] = []
        for i, entry in enumerate(items_raw):
            line = items_raw.line_of(i) if isinstance(items_raw, LineList) else raw.line
            data = check.mapping(entry, line, "an item")
            if data is None:
                continue
            check.keys(data, {"id", "text"}, ("id", "text"), "an item")
            iid = str(check.typed(data, "id", (str, int), str(i))).lower()
            if not iid.isalnum():
                check.add(line, f"item id '{iid}' must be letters or digits (learners type it)")
            if iid in [it.id for it in items]:
                check.add(line, f"item id '{iid}' is used twice")
            items.append(Item(iid, str(check.typed(data, "text", str, "")), line))
        if len(items) < 3:
            check.add(raw.line_of("items"), "an order exercise needs at least three items")
        feedback = check.typed(raw, "feedback", dict, {})
        lines: dict[str, int] = {}
        for key in feedback:
            if str(key).lower() not in [it.id for it in items]:
                check.add(raw.line_of("feedback"), f"feedback for unknown item '{key}'")
            lines[str(key).lower()] = (
                feedback.text_line(key)
                if isinstance(feedback, LineDict)
                else raw.line_of("feedback")
            )
        if spec.reference:
            check.add(
                spec.reference_line,
                "an order exercise takes its answer from the order of 'items'; remove 'reference'",
            )
        return OrderOptions(
            tuple(items), {str(k).lower(): str(v) for k, v in feedback.items()}, lines
        )

    def expected(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        return [it.id for it in spec.options.items]

    def display_order(self, spec: ExerciseSpec, variant: Variant) -> list[Item]:
        items = list(spec.options.items)
        shuffled = items[:]
        random.Random(f"{spec.id}:{variant.seed}:order").shuffle(shuffled)
        if shuffled == items:  # never show the answer itself
            shuffled = shuffled[1:] + shuffled[:1]
        return shuffled

    def shown(self, spec: ExerciseSpec, variant: Variant) -> list[tuple[str, Item]]:
        """(label, item) in the order shown: the letters ``a, b, c, …`` in that order when the
        authored ids are mere labels, else the authored ids. What a face shows, what a learner
        types and what :meth:`check` reads."""
        return labelled(self.display_order(spec, variant))

    def labels(self, spec: ExerciseSpec, variant: Variant) -> dict[str, str]:
        """Authored id → the label this variant shows it under."""
        return {it.id: label for label, it in self.shown(spec, variant)}

    def shown_answer(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        """The right order as this variant's learner types it (labels); :meth:`expected` is
        the same in authored ids."""
        labels = self.labels(spec, variant)
        return [labels[i] for i in self.expected(spec, variant)]

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        opts: OrderOptions = spec.options
        items = [
            {"id": label, "text": opts.item_text(spec, variant, it)}
            for label, it in self.shown(spec, variant)
        ]
        return {"type": "order", "items": items}

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        return (
            "Answer with the ids in order, first to last, separated by spaces, e.g. "
            f"`{self.example(spec, variant)}`."
        )

    def example_candidates(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        ids = [label for label, _ in self.shown(spec, variant)]
        return [" ".join(ids), " ".join(reversed(ids)), " ".join(ids[1:] + ids[:1])]

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        shown = self.shown(spec, variant)
        by_label = dict(shown)
        right = self.shown_answer(spec, variant)
        try:
            given = parse_ids(answer)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        unknown = [g for g in given if g not in by_label]
        if unknown:
            return Verdict.unreadable(
                f"there is no item '{unknown[0]}'; the items are {', '.join(sorted(by_label))}"
            )
        if sorted(given) != sorted(right):
            missing = [label for label, _ in shown if label not in given]
            twice = sorted({g for g in given if given.count(g) > 1})
            what = f"missing {', '.join(missing)}" if missing else f"repeated {', '.join(twice)}"
            return Verdict.unreadable(f"use each item exactly once ({what})")
        if given == right:  # the face says "correct": not twice
            return Verdict.ok("Every step is in its place.")
        opts: OrderOptions = spec.options
        run = longest_ordered([right.index(g) for g in given])
        in_run = {given[i] for i in run}
        out = [g for g in given if g not in in_run]
        parts = [f"Not quite: {len(run)} of {len(right)} steps are in the right relative order."]
        listed = "; ".join(
            f"{g}) {opts.item_text(spec, variant, by_label[g]).rstrip('.')}" for g in out
        )
        parts.append(f"Out of place: {listed}.")
        parts += [
            opts.item_feedback(spec, variant, by_label[g].id)
            for g in out
            if by_label[g].id in opts.feedback
        ]  # a paragraph each: sentences of their own, never run together
        return Verdict.wrong("\n\n".join(parts), score=len(run) / len(right), out_of_place=out)

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        problems = []
        if not self.check(spec, variant, " ".join(self.shown_answer(spec, variant))).passed:
            problems.append(problem(spec, spec.line, "the correct order is not accepted"))
        shown = " ".join(label for label, _ in self.shown(spec, variant))
        if self.check(spec, variant, shown).passed:
            problems.append(problem(spec, spec.line, "the order shown is already accepted"))
        return problems
