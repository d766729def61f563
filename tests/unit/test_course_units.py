"""Unit tests of the course layer's pure pieces: YAML lines, filters, LIS, tolerance wording."""

from __future__ import annotations

import itertools
import math
import threading
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.course.model import Tolerance
from slamcourse.course.templates import angle, mat, num, vec
from slamcourse.course.yamlio import LineDict, load_yaml
from slamcourse.errors import CourseError
from slamcourse.kinds.numeric import describe_tolerance
from slamcourse.kinds.order import longest_ordered
from slamcourse.watch import wait_for_change


def test_yaml_keeps_lines_of_keys_items_and_block_text() -> None:
    data = load_yaml("a: 1\nb:\n  - x\n  - y\nc: |\n  text\n", "f.yaml")
    assert isinstance(data, LineDict)
    assert data.line_of("a") == 1 and data.line_of("c") == 5
    assert data["b"].line_of(1) == 4
    assert data.text_line("c") == 6  # a block scalar's text starts below its key


def test_yaml_errors_name_the_line() -> None:
    with pytest.raises(CourseError, match=r"f.yaml:3: duplicate key 'a' \(first at line 1\)"):
        load_yaml("a: 1\nb: 2\na: 3\n", "f.yaml")
    with pytest.raises(CourseError, match=r"f.yaml:2: YAML syntax error"):
        load_yaml("a: [1\nb: 2\n", "f.yaml")


def test_template_filters() -> None:
    assert num(10609) == "10609" and num(0.141897) == "0.1419" and num(2.0, 3) == "2.000"
    assert (
        angle(math.pi / 4) == "π/4" and angle(-math.pi) == "-π" and angle(3 * math.pi / 2) == "3π/2"
    )
    assert angle(0.1419) == "0.1419"
    assert vec([0.3, -0.09]) == "[0.3, -0.09]"
    assert mat([[1, 0], [0, 1]]) == r"\begin{bmatrix} 1 & 0 \\ 0 & 1 \end{bmatrix}"


def test_tolerance_is_described_as_learners_read_it() -> None:
    assert describe_tolerance(Tolerance(0.01, 1e-9), False) == "within 1%"
    assert describe_tolerance(Tolerance(0.0, 0.005), False) == "within ±0.005"
    assert describe_tolerance(Tolerance(0.01, 0.5), False) == "within ±(0.5 + 1% of the value)"
    assert describe_tolerance(Tolerance(), True) == "exactly"


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(0, 20), max_size=9, unique=True))
def test_longest_ordered_is_increasing_and_maximal(positions: list[int]) -> None:
    run = longest_ordered(positions)
    values = [positions[i] for i in run]
    assert run == sorted(run) and values == sorted(values)
    best = max(
        (
            len(c)
            for r in range(len(positions) + 1)
            for c in itertools.combinations(positions, r)
            if list(c) == sorted(c)
        ),
        default=0,
    )
    assert len(run) == best


@pytest.mark.parametrize("poll", [False, True])
def test_watch_sees_a_save(tmp_path: Path, poll: bool) -> None:
    target = tmp_path / "mine.py"
    target.write_text("a = 1\n")

    def save() -> None:
        time.sleep(0.3)
        target.write_text("a = 2\n")

    threading.Thread(target=save).start()
    assert wait_for_change(target, poll=poll, interval=0.05, timeout=10) == (
        "polling" if poll else "inotify"
    )


def test_watch_times_out_without_a_save(tmp_path: Path) -> None:
    target = tmp_path / "mine.py"
    target.write_text("a = 1\n")
    assert wait_for_change(target, timeout=0.2) == "timeout"
    assert wait_for_change(target, poll=True, interval=0.05, timeout=0.2) == "timeout"


def test_substitution_fast_path_agrees_with_jinja_on_the_whole_course() -> None:
    """Every template of the bundled course renders the same with or without Jinja2."""
    from slamcourse.course import templates
    from slamcourse.course.loader import load_course
    from slamcourse.course.locate import bundled_course_root
    from slamcourse.course.variants import variant
    from slamcourse.kinds import get_kind

    course = load_course(bundled_course_root())
    fast_used = 0
    for exercise_id in course.exercise_ids:
        spec = course.exercise(exercise_id)
        for seed in (0, 1, 2):
            v = variant(spec, seed)
            answer = get_kind(spec.kind).expected(spec, v)
            texts = [spec.prompt, *spec.hints, *(m.message for m in spec.misconceptions)]
            cases = [(t, dict(v.params)) for t in texts]
            cases.append((spec.explanation, {**v.params, "answer": answer}))
            for text, context in cases:
                fast = templates.substitute(text.source, context)
                if fast is None:
                    continue
                fast_used += 1
                slow = templates._compile(text.source).render(**context)
                assert fast.strip() == slow.strip(), (exercise_id, text.source)
    assert fast_used > 100


def test_substitution_declines_what_it_cannot_do() -> None:
    from slamcourse.course.templates import substitute

    assert substitute("x = {{ x | num(2) }} m", {"x": 1.23456}) == "x = 1.23 m"
    assert substitute("{{ a + b }}", {"a": 1, "b": 2}) is None
    assert substitute("{% if a %}y{% endif %}", {"a": 1}) is None
    assert substitute("{{ missing }}", {}) is None
    assert substitute("{{ x | upper }}", {"x": "a"}) is None
    assert (
        substitute(r"$\frac{1}{\sqrt{2}}$ and {{ x }}", {"x": 3}) == r"$\frac{1}{\sqrt{2}}$ and 3"
    )


def test_distribution_entries_are_checked_in_one_place() -> None:
    from slamcourse.course.schema import Checker

    forms = {"int": "int-range", "uniform": "range", "choice": "list", "expr": "text"}
    check = Checker("f.yaml")
    doc = load_yaml(
        "a: {uniform: [-1, 2.5]}\nb: {int: [1, 2.5]}\nc: {choice: []}\nd: {uniform: [3, 1]}\n"
        "e: {int: [1, 3], expr: x}\nf: {expr: 2*x}\n",
        "f.yaml",
    )
    assert check.distribution(doc["a"], forms, "a") == ("uniform", (-1, 2.5))
    assert check.distribution(doc["f"], forms, "f") == ("expr", ("2*x",))
    for key in "bcde":
        assert check.distribution(doc[key], forms, key) is None
    assert [str(p) for p in check.problems] == [
        "f.yaml:2: 'int' of b must be [low, high], whole numbers with low ≤ high",
        "f.yaml:3: 'choice' of c must be a non-empty list",
        "f.yaml:4: 'uniform' of d must be [low, high], numbers with low ≤ high",
        "f.yaml:5: e needs exactly one of int, uniform, choice, expr (found int, expr)",
    ]
