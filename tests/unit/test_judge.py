"""A code exercise's ``judge:``: a reference.py function that decides instead of the tolerance.

The comparison (``grading.returns.compare``) checks the value's form first (the reference's
shape, finite numbers) and only then asks the judge; the grader's one pass over a test set
(``grading.testset.run_cases``) hands the judge each input; the loader accepts the key and
refuses misconceptions beside it; the prompt's rules say that a test decides.
"""

from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

import pytest

from slamcourse.course.loader import load_course, load_exercise
from slamcourse.course.model import Tolerance
from slamcourse.errors import CourseError, GraderError
from slamcourse.grading import testset
from slamcourse.grading.properties import TrustedCallee
from slamcourse.grading.returns import compare
from slamcourse.grading.testset import Case, run_cases
from slamcourse.kinds import get_kind

TOL = Tolerance(rtol=1e-6, atol=1e-9)
calls: list[tuple[Any, Any, dict[str, Any]]] = []


def sum_is_n(got: Any, expected: Any, kwargs: dict[str, Any]) -> str | None:
    """Accepts any list whose entries add up to ``n``."""
    calls.append((got, expected, kwargs))
    total = sum(got)
    return None if abs(total - kwargs["n"]) < 1e-9 else f"the entries add up to {total}"


def test_the_judge_decides_instead_of_the_tolerance() -> None:
    calls.clear()
    want = [1.0, 1.0, 1.0]
    assert compare("array", [0.5, 2.0, 0.5], want, TOL, judge=sum_is_n, kwargs={"n": 3}) is None
    bad = compare("array", [1.0, 1.0, 2.0], want, TOL, judge=sum_is_n, kwargs={"n": 3})
    assert bad is not None and bad.message == "the entries add up to 4.0"
    assert calls[0] == ([0.5, 2.0, 0.5], want, {"n": 3})
    # without a judge the same value is compared with the reference
    assert compare("array", [0.5, 2.0, 0.5], want, TOL) is not None


@pytest.mark.parametrize(
    ("spec", "got", "want", "words"),
    [
        ("array", [1.0, 2.0], [1.0, 1.0, 1.0], "shape"),
        ("array", [[1.0, 2.0, 0.0]], [1.0, 1.0, 1.0], "shape"),
        ("array", [1.0, float("nan"), 2.0], [1.0, 1.0, 1.0], "not a finite number"),
        ("number", "3", 3.0, "expected a number"),
        (("number", "angle"), [1.0], [1.0, 0.5], "expected 2 values"),
        (("number", "boolean"), [1.0, 1], [1.0, True], "True or False"),
        ("number", None, 3.0, "forget to return"),
    ],
)
def test_a_value_of_the_wrong_form_never_reaches_the_judge(
    spec: Any, got: Any, want: Any, words: str
) -> None:
    calls.clear()
    bad = compare(spec, got, want, TOL, judge=sum_is_n, kwargs={"n": 3})
    assert bad is not None and words in bad.message
    assert calls == []


def test_any_finite_value_of_the_right_form_reaches_it() -> None:
    calls.clear()
    seen: list[Any] = []

    def spy(got: Any, expected: Any, kwargs: dict[str, Any]) -> None:
        seen.append(got)
        return None

    assert compare(("integer", "angle", "boolean"), [2.5, 40.0, False], [1, 0.0, True], TOL,
                   judge=spy) is None  # fmt: skip
    assert seen == [[2.5, 40.0, False]]


def test_a_failing_judge_is_the_graders_fault() -> None:
    def broken(got: Any, expected: Any, kwargs: dict[str, Any]) -> str | None:
        raise KeyError("n")

    with pytest.raises(GraderError, match="judge failed"):
        compare("array", [1.0], [1.0], TOL, judge=broken, kwargs={})


def test_the_judge_cannot_change_the_test_input() -> None:
    def meddler(got: Any, expected: Any, kwargs: dict[str, Any]) -> None:
        kwargs["n"] = 99
        got.append(1.0)
        return None

    kwargs = {"n": 3}
    got = [3.0]
    assert compare("array", got, [3.0], TOL, judge=meddler, kwargs=kwargs) is None
    assert kwargs == {"n": 3} and got == [3.0]


def test_run_cases_hands_each_input_to_the_judge() -> None:
    calls.clear()
    cases = [Case({"n": n}, [1.0] * n, "drawn") for n in (1, 2, 3)]
    tests = testset.TestSet("demo/split", 0, cases)

    def split(n: int) -> list[float]:  # a right answer that is not the reference's
        return [n / 2, n / 2] if n == 2 else [float(n)] + [0.0] * (n - 1)

    callee = TrustedCallee(split)
    outcome, _ = run_cases(
        tests,
        lambda many: [callee.call(args) for args in many],
        signature=("n",),
        returns="array",
        tolerance=TOL,
        judge=sum_is_n,
    )
    assert outcome.passed
    assert [kw for _, _, kw in calls] == [{"n": 1}, {"n": 2}, {"n": 3}]

    wrong = TrustedCallee(lambda n: [1.0] * n if n < 3 else [1.0, 1.0, 0.0])
    outcome, _ = run_cases(
        tests,
        lambda many: [wrong.call(args) for args in many],
        signature=("n",),
        returns="array",
        tolerance=TOL,
        judge=sum_is_n,
    )
    assert outcome.failure is not None
    assert outcome.failure.kwargs == {"n": 3}
    assert outcome.failure.message == "the entries add up to 2.0"


# --- the key in a course --------------------------------------------------------------------

REFERENCE = """
def split(n):
    return [1.0] * n


def judge_sum(got, expected, kwargs):
    return None if abs(sum(got) - kwargs["n"]) < 1e-9 else f"the entries add up to {sum(got)}"


def wrong_split(n):
    return [0.0] * n
"""

EXERCISE = """\
format: 1
id: demo/split
kind: code
title: Split a number
prompt: Return n numbers that add up to n.
function: split
signature: [n]
arguments:
  n: {int: [1, 20]}
types:
  n: {type: count, range: [1, 20]}
judge: judge_sum
starter: starter.py
solution: solution.py
reference: split
returns: array
max_examples: 20
explanation: Any split is right.
"""


def _course(tmp_path: Path, extra: str = "") -> Path:
    (tmp_path / "chapters").mkdir()
    (tmp_path / "chapters" / "01-demo.md").write_text(
        "---\nid: demo\ntitle: Demo\n---\n\n```{exercise} demo/split\n```\n", encoding="utf-8"
    )
    folder = tmp_path / "exercises" / "demo"
    folder.mkdir(parents=True)
    (folder / "reference.py").write_text(REFERENCE, encoding="utf-8")
    (folder / "split.yaml").write_text(EXERCISE + extra, encoding="utf-8")
    (folder / "starter.py").write_text(
        "def split(n):\n    raise NotImplementedError\n", encoding="utf-8"
    )
    (folder / "solution.py").write_text(
        "def split(n):\n    return [float(n)] + [0.0] * (n - 1)\n", encoding="utf-8"
    )
    return tmp_path


def test_the_loader_reads_the_key_and_the_rules_say_a_test_decides(tmp_path: Path) -> None:
    root = _course(tmp_path)
    spec = load_course(root).exercise("demo/split")
    assert spec.options.judge == "judge_sum"
    rules = get_kind("code").how_to_answer(spec, None)  # type: ignore[arg-type]
    assert "judged by the test the prompt states" in rules
    assert "|got − expected|" not in rules


def test_misconceptions_beside_a_judge_are_refused(tmp_path: Path) -> None:
    extra = textwrap.dedent(
        """\
        misconceptions:
          - id: zeros
            function: wrong_split
            message: Not zeros.
        """
    )
    root = _course(tmp_path, extra)
    with pytest.raises(CourseError) as info:
        load_exercise(root / "exercises" / "demo" / "split.yaml", root)
    assert any("judged exercise" in p.message for p in info.value.problems)


def test_a_learner_is_judged_and_told_why(tmp_path: Path) -> None:
    root = _course(tmp_path)
    spec = load_course(root).exercise("demo/split")
    kind = get_kind("code")
    right = "def split(n):\n    return [n / 4] * 4 if n > 1 else [1]\n"
    wrong = "def split(n):\n    return [0.5] * n\n"
    assert not kind.check_source(spec, right, "split.py").passed  # 4 entries, not n
    ok = "def split(n):\n    return [0.0] * (n - 1) + [n]\n"
    assert kind.check_source(spec, ok, "split.py").passed
    verdict = kind.check_source(spec, wrong, "split.py")
    assert verdict.status == "failed"
    assert "add up to" in verdict.feedback
    assert "expected" not in verdict.feedback.split("\n")[0]
