"""Answers in percent: where an exercise asks for a percentage (``units: "%"``), ``98.6%`` is
98.6, as the prompt promises; elsewhere a trailing ``%`` stays refused (its meaning is unclear)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from slamcourse.answers import parse_integer, parse_number
from slamcourse.engine import Engine
from slamcourse.errors import AnswerFormatError
from slamcourse.kinds import get_kind
from slamcourse.settings import Settings


@pytest.mark.parametrize("text", ["98.6%", "98.6 %", " 98.6% ", "493/5 %"])
def test_percent_sign_means_the_number_as_written_when_the_answer_is_in_percent(
    text: str,
) -> None:
    assert parse_number(text, "%") == pytest.approx(98.6)


def test_percent_sign_in_whole_numbers_and_unicode_minus() -> None:
    assert parse_integer("25%", "%") == 25
    assert parse_number("−1.5%", "%") == -1.5


@pytest.mark.parametrize(
    ("text", "units"),
    [("98.6%", ""), ("98.6%", "m"), ("98.6 m", "%"), ("5 %%", "%"), ("%", "%"), ("0.5 rad", "%")],
)
def test_other_or_undeclared_units_stay_refused(text: str, units: str) -> None:
    with pytest.raises(AnswerFormatError):
        parse_number(text, units)


@pytest.fixture(scope="module")
def bundled(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Engine]:
    home = tmp_path_factory.mktemp("percent")
    with Engine.open(Settings.from_env(home=home, workspace=Path(home) / "ws")) as engine:
        yield engine


def _number_exercises(engine: Engine) -> list[str]:
    return [
        ex
        for ch in engine.chapters()
        for ex in ch.exercise_ids
        if engine.exercise(ex).kind == "number"
    ]


def test_every_percentage_prompt_accepts_a_percent_sign(bundled: Engine) -> None:
    percent = [ex for ex in _number_exercises(bundled) if bundled.exercise(ex).options.units == "%"]
    assert {"association/gate-tail", "association/chi2-percentile", "graph/chain-sparsity"} <= set(
        percent
    )
    for ex in percent:
        spec = bundled.exercise(ex)
        assert "percentage" in spec.prompt.source.lower(), ex  # the prompt asks for a percentage
        variant = bundled.variant(ex)
        kind = get_kind(spec.kind)
        want = kind.expected(spec, variant)
        for text in (f"{want!r}%", f"{want!r} %"):
            verdict = kind.check(spec, variant, text)
            assert verdict.passed, (ex, text, verdict.feedback)
        as_fraction = kind.check(spec, variant, f"{want / 100!r}%")
        assert as_fraction.status == "failed", ex  # 0.986% is not 98.6%
    # where the answer is not in percent, a trailing % stays refused (0.986 or 98.6?)
    others = [ex for ex in _number_exercises(bundled) if not bundled.exercise(ex).options.units]
    spec = bundled.exercise(others[0])
    variant = bundled.variant(others[0])
    kind = get_kind(spec.kind)
    assert kind.check(spec, variant, f"{kind.expected(spec, variant)!r}%").status == "invalid"
