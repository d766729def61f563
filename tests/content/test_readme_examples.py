"""What the README and the exercises' prompts show as examples: the chapter count is the
course's, and no example answer is a right answer of an exercise (computed by the engine), so an
example never gives an exercise away."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import pytest

from slamcourse.course.variants import variant
from slamcourse.engine import Engine
from slamcourse.kinds import get_kind
from slamcourse.settings import Settings
from tests.conftest import REPO

# the kinds whose answers are the same for every learner up to their numbers (choice and order
# letters are drawn per learner, so a letter example cannot be kept off every learner's answer)
VALUE_KINDS = ("number", "vector", "matrix", "expression")
SEEDS = range(11)  # the canonical variant (0) and ten learners' variants
_EXAMPLE = re.compile(r"(?:for example|e\.g\.)\s+`([^`]+)`")


@pytest.fixture(scope="module")
def engine(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Engine]:
    home = tmp_path_factory.mktemp("examples")
    with Engine.open(Settings.from_env(home=home, workspace=Path(home) / "ws")) as eng:
        yield eng


def _readme() -> str:
    return (REPO / "README.md").read_text(encoding="utf-8")


def _value_exercises(engine: Engine) -> list[str]:
    return [
        ex
        for ch in engine.chapters()
        for ex in ch.exercise_ids
        if engine.exercise(ex).kind in VALUE_KINDS
    ]


def _right_answer_of(engine: Engine, text: str) -> list[str]:
    """The exercises (and variant seeds) that accept ``text`` as a right answer. Formulas are
    tried on every seed (a formula answers every variant); numbers on the lesson's own
    numbers, which the course prints for everyone (--canonical)."""
    hits = []
    for ex in _value_exercises(engine):
        spec = engine.exercise(ex)
        kind = get_kind(spec.kind)
        for seed in SEEDS if spec.kind == "expression" else (0,):
            if kind.check(spec, variant(spec, seed), text).passed:
                hits.append(f"{ex} (variant {seed})")
    return hits


def test_readme_chapter_count_is_the_course_s(engine: Engine) -> None:
    text = _readme()
    # the chapters that teach (the map and the notation page at the end have no exercises)
    n = sum(1 for chapter in engine.chapters() if chapter.exercise_ids)
    ranges = re.findall(r"\bchapters 1–(\d+)", text)
    assert ranges, "the README no longer says which chapters the course has"
    assert all(int(last) == n for last in ranges), (ranges, n)
    assert all(int(k) == n for k in re.findall(r"\b(\d+) chapters\b", text))


def test_readme_answer_examples_are_no_exercise_s_answer(engine: Engine) -> None:
    text = _readme()
    start = text.index("Answers can be")
    paragraph = text[start : text.index("An answer that cannot be read", start)]
    examples = re.findall(r"`([^`]+)`", paragraph)
    assert "[[1, 2], [3, 4]]" in examples and len(examples) >= 8
    for example in examples:
        assert not _right_answer_of(engine, example), f"README's example `{example}` is an answer"


def test_prompt_examples_are_wrong_answers_and_no_exercise_s_answer(engine: Engine) -> None:
    seen = 0
    for ex in _value_exercises(engine):
        spec = engine.exercise(ex)
        kind = get_kind(spec.kind)
        for example in _EXAMPLE.findall(spec.prompt.source):
            seen += 1
            for seed in SEEDS:
                verdict = kind.check(spec, variant(spec, seed), example)
                # readable, wrong and no named mistake: it shows the form, nothing more
                assert verdict.status == "failed" and verdict.misconception is None, (
                    ex,
                    seed,
                    example,
                    verdict.feedback,
                )
            assert not _right_answer_of(engine, example), f"{ex}'s example `{example}`"
    assert seen, "no prompt shows an example any more: the test checks nothing"
