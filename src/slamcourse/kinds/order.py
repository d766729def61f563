"""The ``order`` kind: put steps in order; partial credit by the longest correctly ordered run."""

from __future__ import annotations

import bisect
import random
from dataclasses import dataclass
from typing import Any, ClassVar

from slamcourse.answers import parse_ids
from slamcourse.course.model import ExerciseSpec, Variant
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import LineDict, LineList
from slamcourse.errors import AnswerFormatError, Problem
from slamcourse.kinds.base import Kind, problem
from slamcourse.verdict import Verdict


@dataclass(frozen=True)
class Item:
    id: str
    text: str
    line: int


@dataclass(frozen=True)
class OrderOptions:
    items: tuple[Item, ...]  # in the correct order
    feedback: dict[str, str]


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
        for key in feedback:
            if str(key).lower() not in [it.id for it in items]:
                check.add(raw.line_of("feedback"), f"feedback for unknown item '{key}'")
        if spec.reference:
            check.add(
                spec.reference_line,
                "an order exercise takes its answer from the order of 'items'; remove 'reference'",
            )
        return OrderOptions(tuple(items), {str(k).lower(): str(v) for k, v in feedback.items()})

    def expected(self, spec: ExerciseSpec, variant: Variant) -> list[str]:
        return [it.id for it in spec.options.items]

    def display_order(self, spec: ExerciseSpec, variant: Variant) -> list[Item]:
        items = list(spec.options.items)
        shuffled = items[:]
        random.Random(f"{spec.id}:{variant.seed}:order").shuffle(shuffled)
        if shuffled == items:  # never show the answer itself
            shuffled = shuffled[1:] + shuffled[:1]
        return shuffled

    def form(self, spec: ExerciseSpec, variant: Variant) -> dict[str, Any]:
        items = [{"id": it.id, "text": it.text} for it in self.display_order(spec, variant)]
        return {"type": "order", "items": items}

    def how_to_answer(self, spec: ExerciseSpec, variant: Variant) -> str:
        return "Answer with the ids in order, first to last, e.g. `c a d b`."

    def check(self, spec: ExerciseSpec, variant: Variant, answer: str) -> Verdict:
        right = self.expected(spec, variant)
        try:
            given = parse_ids(answer)
        except AnswerFormatError as exc:
            return Verdict.unreadable(str(exc))
        unknown = [g for g in given if g not in right]
        if unknown:
            return Verdict.unreadable(
                f"there is no item '{unknown[0]}'; the items are {', '.join(sorted(right))}"
            )
        if sorted(given) != sorted(right):
            missing = [r for r in right if r not in given]
            twice = sorted({g for g in given if given.count(g) > 1})
            what = f"missing {', '.join(missing)}" if missing else f"repeated {', '.join(twice)}"
            return Verdict.unreadable(f"use each item exactly once ({what})")
        if given == right:
            return Verdict.ok("Correct: every step is in its place.")
        run = longest_ordered([right.index(g) for g in given])
        in_run = {given[i] for i in run}
        out = [g for g in given if g not in in_run]
        by_id = {it.id: it for it in spec.options.items}
        parts = [f"Not quite: {len(run)} of {len(right)} steps are in the right relative order."]
        parts.append("Out of place: " + ", ".join(f"{g}) {by_id[g].text}" for g in out) + ".")
        parts += [spec.options.feedback[g] for g in out if g in spec.options.feedback]
        return Verdict.wrong(" ".join(parts), score=len(run) / len(right), out_of_place=out)

    def self_test(self, spec: ExerciseSpec, variant: Variant) -> list[Problem]:
        problems = []
        if not self.check(spec, variant, " ".join(self.expected(spec, variant))).passed:
            problems.append(problem(spec, spec.line, "the correct order is not accepted"))
        shown = " ".join(it.id for it in self.display_order(spec, variant))
        if self.check(spec, variant, shown).passed:
            problems.append(problem(spec, spec.line, "the order shown is already accepted"))
        return problems
