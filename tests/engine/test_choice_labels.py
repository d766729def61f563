"""Choice, multi and order answers cannot be guessed from their letters (issue 15, item 3).

Options and items whose ids are mere labels (``a``, ``b``, ``c``, …) are shown in a per-variant
order and relabelled in that order, so the letters a learner sees say nothing about the order
the author wrote them in: a fixed guess ("a", "a b c", "a b c d e") is right no more often than
chance says. The letters shown are the letters graded, the same in the terminal, the browser
and the batch grader, and ``validate`` warns about keys biased in position or length.
"""

from __future__ import annotations

import json
import math
import re
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from slamcourse.cli import main
from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.course.model import ExerciseSpec
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind
from tests.conftest import FIXTURE_COURSE

REAL = load_course(bundled_course_root())
FIXTURE = load_course(FIXTURE_COURSE)
KINDS = ("choice", "multi", "order")
LETTERS = "abcdefghijklmnopqrstuvwxyz"
SEEDS = range(200)


def _entries(spec: ExerciseSpec) -> list[Any]:
    return list(spec.options.items if spec.kind == "order" else spec.options.choices)


def _lettered(spec: ExerciseSpec) -> bool:
    """Ids that are mere labels (the first n letters), not names such as c1…c9."""
    ids = [e.id for e in _entries(spec)]
    return sorted(ids) == list(LETTERS[: len(ids)])


def _of(course: Any, kinds: tuple[str, ...] = KINDS) -> list[ExerciseSpec]:
    specs = [course.exercise(ex) for ex in course.exercise_ids]
    return [s for s in specs if s.kind in kinds]


REAL_LETTERED = [s for s in _of(REAL) if _lettered(s)]


def test_every_lettered_exercise_is_covered() -> None:
    ids = {s.id for s in REAL_LETTERED}
    assert {
        "state/correlation-order",
        "factor-graphs/slam-steps",
        "capstone/frame-pipeline",
        "capstone/loop-closure-checks",
    } <= ids
    # only named options (the Jacobian's columns c1…c9) keep their ids and authored order
    assert {s.id for s in _of(REAL)} - ids == {"observation/jacobian-columns"}
    for spec in REAL_LETTERED:  # every lettered one is labelled a, b, c, … as shown
        for seed in (0, 1, 2):
            form = get_kind(spec.kind).form(spec, variant(spec, seed))
            shown = [o["id"] for o in form["items" if spec.kind == "order" else "options"]]
            assert shown == list(LETTERS[: len(shown)]), (spec.id, seed)


def _right_answers(spec: ExerciseSpec) -> list[tuple[str, ...]]:
    """The right answer, as the learner types it, for each of :data:`SEEDS`."""
    kind = get_kind(spec.kind)
    found = []
    for seed in SEEDS:
        v = variant(spec, seed)
        form = kind.form(spec, v)
        shown = form["items"] if spec.kind == "order" else form["options"]
        label_of = {o["text"]: o["id"] for o in shown}
        right = kind.expected(spec, v)
        texts = {e.id: e.text for e in _entries(spec)}
        labels = [label_of[texts[r]] for r in right]
        found.append(tuple(labels) if spec.kind == "order" else tuple(sorted(labels)))
    return found


@pytest.mark.parametrize("spec", REAL_LETTERED, ids=lambda s: s.id)
def test_a_fixed_guess_is_right_no_more_often_than_chance(spec: ExerciseSpec) -> None:
    n = len(_entries(spec))
    answers = _right_answers(spec)
    k = len(answers[0])
    if spec.kind == "order":
        chance = 1 / (math.factorial(n) - 1)  # the order shown is never the answer
        guess = tuple(LETTERS[:n])  # "a b c d e": the order shown
        margin = 0.02
    else:
        chance = 1 / math.comb(n, k) if spec.kind == "multi" else 1 / n
        guess = tuple(LETTERS[:k])  # "a", or "a b c" for three right options
        margin = 0.1
    assert answers.count(guess) / len(SEEDS) <= chance + margin, (spec.id, guess)
    # nor any other fixed answer: no letter (set, order) is the key in most variants
    most, times = Counter(answers).most_common(1)[0]
    assert times / len(SEEDS) <= chance + margin + 0.05, (spec.id, most, times)


@pytest.mark.parametrize(
    "spec", [s for s in REAL_LETTERED if s.kind == "order"], ids=lambda s: s.id
)
def test_the_order_shown_is_never_the_answer(spec: ExerciseSpec) -> None:
    n = len(_entries(spec))
    assert tuple(LETTERS[:n]) not in _right_answers(spec)


CASES = _of(REAL) + _of(FIXTURE)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    spec=st.sampled_from(CASES),
    seed=st.integers(min_value=0, max_value=2**31 - 1),
    pick=st.integers(min_value=0, max_value=25),
)
def test_the_letters_shown_are_the_letters_graded(spec: ExerciseSpec, seed: int, pick: int) -> None:
    """Whatever the variant: the labels are a, b, c, … in the order shown (or the names as
    written), the answer spelled in them passes, and feedback names the label shown."""
    kind = get_kind(spec.kind)
    v = variant(spec, seed)
    form = kind.form(spec, v)
    shown = form["items"] if spec.kind == "order" else form["options"]
    labels = [o["id"] for o in shown]
    text_of = {o["id"]: o["text"] for o in shown}
    entry_of = {e.text: e for e in _entries(spec)}
    if _lettered(spec):
        assert labels == list(LETTERS[: len(labels)])
    else:
        assert sorted(labels) == sorted(e.id for e in _entries(spec))
    assert form == kind.form(spec, variant(spec, seed))  # a function of (id, seed)
    right = set(kind.expected(spec, v))  # authored ids
    label = labels[pick % len(labels)]
    picked = entry_of[text_of[label]]
    if spec.kind == "order":
        authored = [e.id for e in _entries(spec)]
        answer = sorted(labels, key=lambda lb: authored.index(entry_of[text_of[lb]].id))
        assert kind.check(spec, v, " ".join(answer)).passed
        i = answer.index(label)
        if i + 1 < len(answer):  # swap the picked item with the next one: it is out of place
            answer[i], answer[i + 1] = answer[i + 1], answer[i]
            verdict = kind.check(spec, v, " ".join(answer))
            assert not verdict.passed
            out = verdict.details["out_of_place"]  # one of the two, by the label shown
            assert len(out) == 1 and out[0] in (answer[i], answer[i + 1])
            assert f"Out of place: {out[0]}) {text_of[out[0]].rstrip('.')}." in verdict.feedback
        return
    if spec.kind == "choice":
        verdict = kind.check(spec, v, label)
        assert verdict.passed == (picked.id in right)
        assert picked.feedback.split("{")[0].strip() in verdict.feedback
        return
    key = [lb for lb in labels if entry_of[text_of[lb]].id in right]
    assert kind.check(spec, v, " ".join(reversed(key))).passed
    if picked.id not in right:
        verdict = kind.check(spec, v, " ".join([*key, label]))
        assert not verdict.passed and f"{label}) does not apply." in verdict.feedback


# ------------------------------------------------------------------------ the three faces


def _screen_options(screen: str) -> list[tuple[str, str]]:
    """(label, text) of the bulleted options of a `slamcourse show` screen."""
    found: list[tuple[str, str]] = []
    for line in screen.splitlines():
        head = re.match(r"• ([a-z0-9]+)\) (.*)", line)
        if head:
            found.append((head[1], head[2]))
        elif found and line.startswith("  ") and not line.startswith("   "):
            found[-1] = (found[-1][0], f"{found[-1][1]} {line.strip()}")
        elif found and not line.startswith("  "):
            break
    return found


def _plain(text: str) -> str:
    """Text as the terminal shows it (math as Unicode), spaces collapsed."""
    from slamcourse.render.math import latex_to_unicode

    text = re.sub(r"\$([^$]+)\$", lambda m: latex_to_unicode(m.group(1)), text)
    return re.sub(r"\s+", " ", text).strip()


def test_terminal_browser_and_batch_agree_on_labels(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """One learner, the real course: an exercise with variants (the learner's own seed) and a
    multi exercise. The terminal's screen, the browser API's payload and the batch grader's
    verdicts name the same letters."""
    from slamcourse.batch.grade import GradeOptions, grade_submission
    from slamcourse.batch.submission import build, write
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings
    from slamcourse.web.app import create_app
    from tests.web.conftest import HOST, TOKEN

    home = tmp_path / "home"
    monkeypatch.setenv("SLAMCOURSE_HOME", str(home))
    one, many = "consistency/diagnose", "graph/variable-ordering"
    screens: dict[str, list[tuple[str, str]]] = {}
    for ex in (one, many):
        assert main(["show", ex]) == 0
        screens[ex] = _screen_options(capsys.readouterr().out)
        assert [lb for lb, _ in screens[ex]] == list(LETTERS[: len(screens[ex])])

    settings_ = Settings.from_env(home=home, workspace=tmp_path / "workspace")
    with Engine.open(settings_) as engine:
        seed = engine.variant(one).seed
        assert seed != 0  # the learner's own variant
        client = create_app(engine, token=TOKEN, hosts=[HOST]).test_client()
        assert client.get(f"/?token={TOKEN}").status_code == 303
        for ex in (one, many):
            data = client.get(f"/api/exercise/{ex}", headers={"Origin": f"http://{HOST}"})
            options = data.get_json()["form"]["options"]
            browser = [(o["id"], _plain(o["text"])) for o in options]
            assert browser == [(lb, _plain(text)) for lb, text in screens[ex]]

        # the learner answers in the terminal with the letters on the screen
        spec = engine.exercise(one)
        key = spec.options.by_id(get_kind("choice").expected(spec, engine.variant(one))[0])
        right = next(lb for lb, text in screens[one] if _plain(text) == _plain(key.text))
        wrong = {_plain(c.text) for c in engine.exercise(many).options.choices if not c.correct}
        wrong_many = next(lb for lb, text in screens[many] if _plain(text) in wrong)
        assert main(["check", one, "--answer", right]) == 0
        assert main(["check", many, "--answer", wrong_many]) == 1
        said = _plain(capsys.readouterr().out)
        assert f"{wrong_many}) does not apply." in said
        sub = build(engine, learner_name="ada")
    path = write(sub, tmp_path / "ada.zip")
    result = grade_submission(path, GradeOptions(hidden_runs=0))
    assert result.status == "graded", result.error
    graded = {e.exercise: e for e in result.exercises}
    assert (graded[one].status, graded[one].variant) == ("passed", seed)
    assert graded[many].status == "failed"
    assert f"{wrong_many}) does not apply." in graded[many].feedback
    assert _plain(graded[many].feedback) in said


# ------------------------------------------------------------------------ validate's warning


def _course(root: Path, choices: list[list[tuple[str, bool]]]) -> Path:
    """A one-chapter course of single-choice exercises: ``choices[i]`` lists (text, correct)."""
    (root / "chapters").mkdir(parents=True)
    (root / "exercises" / "quiz").mkdir(parents=True)
    blocks = []
    for i, options in enumerate(choices, 1):
        lines = [
            "format: 1",
            f"id: quiz/q{i}",
            "kind: choice",
            f"title: Question {i}",
            "prompt: Which one?",
            "choices:",
        ]
        for letter, (text, correct) in zip(LETTERS, options, strict=False):
            flag = ", correct: true" if correct else ""
            lines.append(f"  - {{id: {letter}, text: {json.dumps(text)}{flag}}}")
        lines.append("explanation: Because.")
        (root / "exercises" / "quiz" / f"q{i}.yaml").write_text("\n".join(lines) + "\n")
        blocks.append(f"```{{exercise}} quiz/q{i}\n```\n")
    chapter = "---\nid: quiz\ntitle: A quiz\n---\n\nSome prose.\n\n" + "\n".join(blocks)
    (root / "chapters" / "01-quiz.md").write_text(chapter)
    return root


LONG = "The right one, explained at length with every qualification it needs"


def test_validate_warns_about_keys_biased_in_position_and_length(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    biased = _course(
        tmp_path / "biased",
        [[(LONG, True), ("No.", False), ("Never.", False), ("Nope.", False)]] * 4,
    )
    assert main(["validate", str(biased)]) == 0  # a warning, not a problem
    out = capsys.readouterr().out
    warnings = [line for line in out.splitlines() if ": warning: " in line]
    for i in range(1, 5):
        where = f"exercises/quiz/q{i}.yaml:7: warning: "
        assert f"{where}the correct choice 'a' is written first of the options, as in 4 of 4" in out
        assert f"{where}the correct choice 'a' is the longest option, as in 4 of 4" in out
    assert len(warnings) == 8
    assert "shuffled and relabelled per variant, so this does not give the answer away" in out
    assert "shuffling hides its position but not its length, so learners can guess it" in out
    assert "0 problems, 8 warnings" in out

    assert main(["validate", str(biased), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["ok"] and data["problems"] == [] and len(data["warnings"]) == 8

    # keys written at every place, none the longest: nothing to warn about
    options = ["Alpha one.", "Beta two.", "Gamma three.", "Delta four."]
    balanced = _course(
        tmp_path / "balanced",
        [[(text, i == k) for i, text in enumerate(options)] for k in range(4)],
    )
    assert main(["validate", str(balanced)]) == 0
    out = capsys.readouterr().out
    assert "warning" not in out, out


def test_the_bundled_course_gets_the_warnings_it_deserves() -> None:
    """The real course's fixed keys follow no habit: the correct option is written at every
    place and is rarely the longest, and a multi exercise's right options are not the first
    ones written (most once were: their options were rewritten and reordered; the bias check
    itself is tested on a fixture course above). Its explanations name steps by their text,
    not by the letters they were written with (the four that did were rewritten)."""
    from slamcourse.validate import key_bias, letters_named

    found = [str(w) for w in key_bias(_of(REAL, ("choice", "multi")))]
    assert found == [], found
    named = {w.path for spec in _of(REAL) for w in letters_named(spec)}
    assert named == set(), named
