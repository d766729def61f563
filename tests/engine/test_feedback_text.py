"""Feedback as both faces show it: only course text is Markdown; the engine's words and the
learner's own text are shown as written; option feedback is a template; a sentence that starts
with code or a file name keeps its case; "correct" is said once (issue 15, items 8–11)."""

from __future__ import annotations

import io
import re
from collections.abc import Iterator
from pathlib import Path

import pytest

from slamcourse.cli import Out, main, print_result
from slamcourse.course.loader import load_course
from slamcourse.course.model import Text
from slamcourse.engine import Engine, Result
from slamcourse.kinds import get_kind
from slamcourse.render.terminal import render_markdown
from slamcourse.settings import Settings
from slamcourse.validate import validate_exercise
from slamcourse.verdict import Verdict, capitalised, engine_text, literal
from slamcourse.web.markdown import to_html
from tests.conftest import FIXTURE_COURSE

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def engine(tmp_path: Path) -> Iterator[Engine]:
    settings = Settings.from_env(
        course=FIXTURE_COURSE, home=tmp_path / "h", workspace=tmp_path / "w"
    )
    with Engine.open(settings) as eng:
        yield eng


# ------------------------------------------------------------------ 8: literal engine text


def test_product_star_is_shown_in_both_faces(engine: Engine) -> None:
    feedback = engine.submit("basics/distance", "2 pi").verdict.feedback
    said = "for a product write '*', e.g. 2*pi"
    assert said in render_markdown(feedback, width=200)
    html = str(to_html(feedback))
    assert said in html and "<em>" not in html


def test_a_learners_math_is_never_typeset(engine: Engine) -> None:
    feedback = engine.submit("basics/pick", "$x$").verdict.feedback
    assert "'$x$'" in render_markdown(feedback, width=200)  # the terminal would drop the $
    html = str(to_html(feedback))
    assert "'$x$'" in html and 'class="math' not in html


@pytest.mark.parametrize(
    "text",
    [
        "for a product write '*', e.g. 2*pi",
        "cannot read '$x$ and $$y$$' as a formula",
        "cannot read '[a](http://example.org)' or '<b>bold</b>' or '&amp;'",
        "'_x_' and '__y__' and '~~z~~' and 'a\\b' and '`code`'",
        "answer:\n# not a heading\n- not a list\n1. not a list\n> not a quote",
        "range_bearing.py:4: x < 3",
    ],
)
def test_literal_text_renders_as_written(text: str) -> None:
    md = literal(text)
    assert render_markdown(md, width=500).split() == text.split()
    html = str(to_html(md))
    assert not re.search(r"<(em|strong|a|code|h1|ul|ol|li|blockquote|s|del)\b", html)
    assert 'class="math' not in html


def test_engine_text_keeps_its_own_code_spans() -> None:
    md = engine_text("f in syn.py is not a function; write `def f(x_1, *args):`, not 2*x")
    assert str(to_html(md)).count("<code>def f(x_1, *args):</code>") == 1
    assert "not 2*x" in render_markdown(md, width=200)
    assert Verdict.unreadable("2*pi").feedback == "2\\*pi"


# ------------------------------------------------------------------ 9: option feedback


def test_every_option_feedback_of_the_course_is_rendered() -> None:
    course = load_course(REPO)
    checked = 0
    for ex_id in course.exercise_ids:
        spec = course.exercise(ex_id)
        if spec.kind not in ("choice", "multi"):
            continue
        kind = get_kind(spec.kind)
        from slamcourse.course import variants

        for seed in (0, 1, 2) if spec.has_variants else (0,):
            variant = variants.variant(spec, seed)
            for label, _ in kind.shown(spec, variant):
                text = kind.check(spec, variant, label).feedback
                assert "{{" not in text and "{%" not in text, (ex_id, label, text)
                checked += 1
            for option in kind.form(spec, variant)["options"]:
                assert "{{" not in option["text"], (ex_id, option)
    assert checked > 50


def test_scene_feedback_speaks_of_the_variants_numbers() -> None:
    course = load_course(REPO)
    spec = course.exercise("jcbb/scene-greedy")
    kind = get_kind("choice")
    from slamcourse.course import variants

    variant = variants.variant(spec, 0)
    texts = [kind.check(spec, variant, label).feedback for label, _ in kind.shown(spec, variant)]
    assert any("($d^2$ 0.10)" in t for t in texts), texts


# ------------------------------------------------------------------ 10: validate renders all


def _break(course: Path, exercise: str, old: str, new: str) -> None:
    path = course / "exercises" / f"{exercise}.yaml"
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_validate_reports_a_broken_option_feedback_at_its_line(course_copy: Path) -> None:
    _break(
        course_copy,
        "basics/pick",
        "feedback: That is a sensor.}",
        'feedback: "That is {{ no_such_name | num }} a sensor."}',
    )
    problems = validate_exercise(load_course(course_copy), "basics/pick", 3)
    lines = (course_copy / "exercises/basics/pick.yaml").read_text().splitlines()
    line = next(i for i, t in enumerate(lines, 1) if "no_such_name" in t)
    found = [p for p in problems if p.line == line]
    assert found, problems
    assert (
        "template error in the option feedback" in found[0].message
        and "no_such_name" in found[0].message
    )


def test_validate_reports_template_syntax_left_in_the_output(course_copy: Path) -> None:
    _break(
        course_copy,
        "basics/steps",
        "u: You can only update after measuring.",
        "u: \"You can only update after {{ '{{' }} measuring.\"",
    )
    problems = validate_exercise(load_course(course_copy), "basics/steps", 3)
    assert any("still holds '{{'" in p.message and p.line for p in problems), problems


def test_validate_renders_the_real_heading_message_on_every_variant() -> None:
    problems = validate_exercise(load_course(REPO), "ekf-slam/heading-update", 25)
    assert problems == []
    spec = load_course(REPO).exercise("ekf-slam/heading-update")
    from slamcourse.course import templates, variants

    message = spec.misconceptions[0].message
    for seed in range(1, 6):
        p = variants.variant(spec, seed).params
        out = templates.render(spec, Text(message.source, message.line), dict(p))
        apart = p["compass"] - p["theta"] + 2 * 3.141592653589793
        assert f"only {apart:.2f} rad apart" in out
        assert "hundredths" not in out


# ------------------------------------------------------------------ 11: order, case, "correct"


def test_order_feedback_is_one_paragraph_per_sentence_group(engine: Engine) -> None:
    shown = [o["id"] for o in engine.pose("basics/steps").form["items"]]
    wrong = " ".join(reversed(sorted(shown, key=["p", "m", "u"].index)))
    feedback = engine.submit("basics/steps", wrong).verdict.feedback
    paragraphs = feedback.split("\n\n")
    assert paragraphs[0].startswith("Not quite:")
    assert paragraphs[1].startswith("Out of place:")
    assert "You can only update after measuring." in paragraphs
    assert str(to_html(feedback)).count("<p>") == len(paragraphs)


def test_correct_is_not_said_in_the_feedback(engine: Engine) -> None:
    """The faces' status labels say it ("✓ passed", "✓ Correct"); the feedback does not."""
    for ex, answer in [("basics/steps", "p m u"), ("basics/pick", None)]:
        if answer is None:
            form = engine.pose(ex, canonical=True).form
            answer = next(o["id"] for o in form["options"] if o["text"] == "A pose graph optimiser")
        verdict = engine.submit(ex, answer).verdict
        assert verdict.passed and "correct" not in verdict.feedback.lower(), verdict.feedback


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("syn.py:1: syntax error: invalid syntax", "syn.py:1: syntax error"),
        ("mahalanobis(nu0=1.5, S=2) raised ValueError", "mahalanobis(nu0=1.5, S=2) raised"),
        ("range_bearing in syn.py is not a function", "range_bearing in syn.py"),
        (
            "mahalanobis in a.py is not a function; write `def mahalanobis(nu, S):`",
            "mahalanobis in a.py",
        ),
        ("nu0 is not defined", "nu0 is not defined"),
        ("expected 2 entries, but your answer has 1 entry", "Expected 2 entries"),
    ],
)
def test_the_terminal_never_capitalises_code_or_a_file_name(text: str, shown: str) -> None:
    stream = io.StringIO()
    result = Result(
        "basics/range-bearing", 0, Verdict.unreadable(text), False, False, None, None, "pending", 0
    )
    print_result(Out(stream, no_color=True), result)
    assert stream.getvalue().splitlines()[1].startswith(shown)
    assert capitalised(text).startswith(shown)


def test_a_syntax_error_names_its_file_as_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    syn = tmp_path / "syn.py"
    syn.write_text("def range_bearing(dx, dy, theta)\n    return 1\n")
    main(["--course", str(FIXTURE_COURSE), "check", "basics/range-bearing", "--file", str(syn)])
    out = capsys.readouterr().out
    assert "syn.py:1" in out and "Syn.py" not in out
