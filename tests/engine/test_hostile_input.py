"""Hostile input never crashes: any answer text gets a Verdict, any course file a path:line.

Policies under test (docs/grading.md "Answer text", docs/authoring.md "Course files"):

- an answer with invalid UTF-8 or a lone surrogate is an ``invalid`` verdict ("unreadable",
  no attempt counted), and it is still logged, escaped;
- diagnosing a wrong number never raises, whatever the float;
- a course file that is not UTF-8, not readable, or not YAML is a ``path:line`` problem.
"""

from __future__ import annotations

import math
import os
import random
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from slamcourse.answers import decode_answer
from slamcourse.course import variants
from slamcourse.course.loader import Course, load_course
from slamcourse.course.locate import bundled_course_root, course_root
from slamcourse.course.model import ExerciseSpec, Variant
from slamcourse.engine import Engine
from slamcourse.errors import AnswerFormatError, CourseError, UsageError
from slamcourse.kinds import get_kind
from slamcourse.progress import Progress
from slamcourse.settings import Settings as EngineSettings
from slamcourse.validate import validate_exercise
from slamcourse.verdict import STATUSES, Verdict
from tests.conftest import FIXTURE_COURSE, REPO

FIXTURE = load_course(FIXTURE_COURSE)
REAL = load_course(bundled_course_root())
# every answer kind once (the fixture course), plus real exercises of the kinds that compute
REAL_IDS = [
    "observation/predicted-bearing",
    "state/covariance-growth",
    "state/covariance-entries",
    "observation/bearing-derivative",
    "observation/jacobian-matrix",
    "association/nearest-neighbour-bug",
    "factor-graphs/slam-steps",
]


def _answerable() -> list[tuple[str, str]]:
    found = [("fixture", ex) for ex in FIXTURE.exercise_ids]
    found += [("real", ex) for ex in REAL_IDS]
    return [(c, ex) for c, ex in found if _course(c).exercise(ex).kind != "code"]


def _course(name: str) -> Course:
    return FIXTURE if name == "fixture" else REAL


NO_RECORD = EngineSettings.from_env(record=False)


def grade(course: str, exercise_id: str, answer: str, seed: int = 0) -> Verdict:
    engine = Engine(_course(course), NO_RECORD)
    return engine.submit(exercise_id, answer, seed=seed).verdict


def test_the_property_test_covers_every_answer_kind() -> None:
    kinds = {_course(c).exercise(ex).kind for c, ex in _answerable()}
    assert kinds == {"number", "vector", "matrix", "expression", "choice", "multi", "order", "line"}


# ------------------------------------------------------------------ 2. answer text


def test_decode_answer_policy() -> None:
    assert decode_answer("π/4 − 1") == "π/4 − 1"
    assert decode_answer("π/4".encode()) == "π/4"
    with pytest.raises(AnswerFormatError, match=r"character 2 .*byte 0x80 is not UTF-8"):
        decode_answer("6\udc80")  # what argv holds for the bytes 36 80 (surrogateescape)
    with pytest.raises(AnswerFormatError, match=r"character 3 .*byte 0xff is not UTF-8"):
        decode_answer(b"\xcf\x80/\xff")
    with pytest.raises(AnswerFormatError, match=r"character 1 .*lone UTF-16 surrogate U\+D800"):
        decode_answer("\ud800")


@pytest.mark.parametrize("answer", ["\ud800", "6\udc80", "[1, 2\udfff]", "a\ud83d b"])
@pytest.mark.parametrize(("course", "exercise_id"), _answerable())
def test_unreadable_text_is_an_invalid_verdict_in_every_kind(
    course: str, exercise_id: str, answer: str
) -> None:
    verdict = grade(course, exercise_id, answer)
    assert verdict.status == "invalid"
    assert verdict.feedback.startswith("unreadable answer: character")
    verdict.feedback.encode("utf-8")  # printable and storable: it never echoes the character


def test_unreadable_answer_is_logged_escaped_and_not_counted(tmp_path: Path) -> None:
    """Engine.submit with progress: this raised UnicodeEncodeError in record_attempt."""
    settings_ = EngineSettings(home=tmp_path, workspace=tmp_path / "ws", course=FIXTURE_COURSE)
    with Engine(FIXTURE, settings_, Progress.open(tmp_path / "p.sqlite3")) as engine:
        verdict = engine.submit("basics/count", "\ud800").verdict
        assert verdict.status == "invalid"
        state = engine.state("basics/count")
        assert state.attempts == 0
        assert engine.progress is not None
        (logged,) = engine.progress.attempts("basics/count")
        assert logged.answer == "\\ud800"
        assert logged.status == "invalid"


def test_cli_answer_with_an_undecodable_byte_is_unreadable(tmp_path: Path) -> None:
    """``--answer=$'6\\x80'``: Python hands the CLI '6\\udc80' (surrogateescape)."""
    env = {
        **os.environ,
        "PYTHONPATH": str(REPO / "src"),
        "SLAMCOURSE_HOME": str(tmp_path),
        "SLAMCOURSE_COURSE": str(FIXTURE_COURSE),
        "NO_COLOR": "1",
        "PYTHONIOENCODING": "utf-8",
    }
    done = subprocess.run(
        [sys.executable, "-m", "slamcourse", "check", "basics/count", b"--answer=6\x80"],
        env=env,
        capture_output=True,
        timeout=60,
    )
    out = done.stdout.decode() + done.stderr.decode()
    assert "Traceback" not in out
    assert done.returncode == 1, out
    assert "Unreadable answer: character 2 is not text (the byte 0x80 is not UTF-8)" in out
    assert "no attempt counted" in out


def test_code_source_with_a_lone_surrogate_is_unreadable_at_its_line() -> None:
    spec = FIXTURE.exercise("basics/range-bearing")
    source = "import math\n\ndef range_bearing(dx, dy):\n    return '\udc80'\n"
    verdict = get_kind("code").check(spec, get_variant(spec), source)
    assert verdict.status == "invalid"
    assert verdict.feedback.startswith("range_bearing.py:4: a character is not text")


def get_variant(spec: ExerciseSpec) -> Variant:
    return variants.variant(spec, 0)


# ------------------------------------------------------------------ 3. extreme numbers


@pytest.mark.parametrize(
    ("exercise_id", "answer"),
    [
        ("observation/predicted-bearing", "1e308"),  # got / want overflowed: round(inf)
        ("observation/predicted-bearing", "-1.7976931348623157e308"),
        ("state/covariance-growth", "4.9e-324"),  # got / want underflowed: log10(0)
        ("state/covariance-growth", "2.2250738585072014e-308"),
        ("state/covariance-growth", "-5e-324"),
    ],
)
def test_extreme_numbers_are_diagnosed_without_raising(exercise_id: str, answer: str) -> None:
    verdict = grade("real", exercise_id, answer)
    assert verdict.status == "failed"
    assert "factor of 10" not in verdict.feedback


def test_factor_of_ten_is_still_named() -> None:
    verdict = grade("fixture", "basics/distance", "0.05")  # 5 / 100
    assert "factor of 10^-2" in verdict.feedback


# ------------------------------------------------------------------ property: any text, any float

_ALPHABET = st.one_of(
    st.characters(categories=["Cs"]),  # lone surrogates
    st.characters(exclude_categories=()),  # anything else, controls included
    st.sampled_from("0123456789.,;-+eE[]() /*^πpix√"),  # enough to look like an answer
)
_FLOATS = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True)
_FORMATS: list[Callable[[float], str]] = [
    repr,
    str,
    lambda x: f"{x:.17g}",
    lambda x: f"{x:e}",
    lambda x: f"[{x!r}, {x!r}]",
    lambda x: f"[[{x!r}, 0], [0, {x!r}]]",
    lambda x: f"{x!r}*x",
]
_ANSWERS = st.one_of(
    st.text(_ALPHABET, max_size=40),
    st.builds(lambda x, f: f(x), _FLOATS, st.sampled_from(_FORMATS)),
    st.sampled_from(["1e308", "-1e308", "4.9e-324", "5e-324", "1.7976931348623157e308", "0"]),
)


@pytest.mark.parametrize(("course", "exercise_id"), _answerable())
@settings(
    max_examples=60,
    deadline=None,
    database=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)
@given(answer=_ANSWERS)
def test_any_answer_gets_a_verdict(course: str, exercise_id: str, answer: str) -> None:
    verdict = grade(course, exercise_id, answer)
    assert isinstance(verdict, Verdict)
    assert verdict.status in STATUSES and verdict.status != "error"
    verdict.feedback.encode("utf-8")


# the grader may run Hypothesis itself inside this test: to draw the test inputs when no current
# recording is shipped, and to shrink a failing input
@settings(
    max_examples=10,
    deadline=None,
    database=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.nested_given],
)
@given(source=st.one_of(st.text(_ALPHABET, max_size=60), st.sampled_from(["a\x00b", "\ufeff"])))
def test_any_source_text_gets_a_verdict(source: str) -> None:
    """The code kind too (each example spawns a sandbox worker, hence few examples)."""
    spec = FIXTURE.exercise("basics/range-bearing")
    verdict = get_kind("code").check(spec, get_variant(spec), source)
    assert verdict.status in ("invalid", "failed"), verdict
    assert ":None" not in verdict.feedback
    verdict.feedback.encode("utf-8")


@settings(max_examples=200, deadline=None, database=None, derandomize=True)
@given(got=_FLOATS.filter(math.isfinite), want=_FLOATS.filter(lambda w: math.isfinite(w)))
def test_number_diagnosis_never_raises(got: float, want: float) -> None:
    kind = get_kind("number")
    for exercise_id in ("basics/distance", "basics/heading"):
        text = kind._diagnose(FIXTURE.exercise(exercise_id), got, want)  # type: ignore[attr-defined]
        assert isinstance(text, str)


# ------------------------------------------------------------------ 4. hostile course files


def _edit_bytes(path: Path, old: bytes, new: bytes) -> None:
    data = path.read_bytes()
    assert old in data
    path.write_bytes(data.replace(old, new, 1))


def _random_yaml(course: Path) -> None:
    (course / "exercises/basics/distance.yaml").write_bytes(random.Random(1).randbytes(400))


def _title_byte(course: Path) -> None:
    _edit_bytes(course / "exercises/basics/distance.yaml", b"title: ", b"title: caf\xe9 ")


def _prose_byte(course: Path) -> None:
    _edit_bytes(course / "chapters/01-basics.md", b"Angles are", b"Angles \xff are")


def _chapter_symlink_loop(course: Path) -> None:
    os.symlink("loop.md", course / "chapters/loop.md")


def _chapter_is_a_folder(course: Path) -> None:
    (course / "chapters/02-folder.md").mkdir()


def _control_character(course: Path) -> None:
    _edit_bytes(course / "exercises/basics/count.yaml", b"title: ", b"title: \x07")


def _deep_nesting(course: Path) -> None:
    path = course / "exercises/basics/count.yaml"
    path.write_text(path.read_text() + "tags: " + "[" * 3000 + "]" * 3000 + "\n")


def _solution_byte(course: Path) -> None:
    path = course / "exercises/basics/solutions/range_bearing.py"
    path.write_bytes(path.read_bytes() + b"\n# \xff\n")


def _line_of(path: Path, needle: bytes) -> int:
    data = path.read_bytes()
    return data[: data.index(needle)].count(b"\n") + 1


@pytest.mark.parametrize(
    ("breaks", "exercise", "where", "words"),
    [
        (_random_yaml, "distance", "exercises/basics/distance.yaml:1", "is not UTF-8"),
        (_title_byte, "distance", "exercises/basics/distance.yaml:{title}", "0xe9 (column 11)"),
        (_prose_byte, None, "chapters/01-basics.md:{prose}", "byte 0xff (column 8) is not UTF-8"),
        (_chapter_symlink_loop, None, "chapters/loop.md", "Too many levels of symbolic links"),
        (_chapter_is_a_folder, None, "chapters/02-folder.md", "cannot read this file"),
        (_control_character, "count", "exercises/basics/count.yaml:{count_title}", "U+0007 is"),
        (_deep_nesting, "count", "exercises/basics/count.yaml", "nested too deeply"),
        (_solution_byte, "range-bearing", "exercises/basics/solutions/range_bearing.py:", "0xff"),
    ],
    ids=lambda v: v.__name__[1:] if callable(v) else "",
)
def test_hostile_course_file_is_a_located_problem(
    course_copy: Path,
    breaks: Callable[[Path], None],
    exercise: str | None,
    where: str,
    words: str,
) -> None:
    """What ``validate`` reports (only the broken part is validated, to keep this fast)."""
    lines = {
        "title": _line_of(course_copy / "exercises/basics/distance.yaml", b"title: "),
        "prose": _line_of(course_copy / "chapters/01-basics.md", b"Angles are"),
        "count_title": _line_of(course_copy / "exercises/basics/count.yaml", b"title: "),
    }
    breaks(course_copy)
    course = load_course(course_copy)
    found = list(course.problems)
    if exercise is not None:
        found += validate_exercise(course, f"basics/{exercise}", 1)
    problems = [str(p) for p in found]
    located = where.format(**lines)
    assert any(p.startswith(located) and words in p for p in problems), problems


@pytest.mark.parametrize(
    ("exercise", "function", "body"),
    [("count", "def count(n):", "10**400"), ("offset", "def offset(a, b):", "[10**400, 1]")],
)
def test_reference_answer_too_large_for_a_float_is_a_located_problem(
    course_copy: Path, exercise: str, function: str, body: str
) -> None:
    path = course_copy / "exercises/basics/reference.py"
    path.write_text(path.read_text().replace(function, f"{function}\n    return {body}\n", 1))
    course = load_course(course_copy)
    problems = [str(p) for p in validate_exercise(course, f"basics/{exercise}", 0)]
    assert any(
        p.startswith(f"exercises/basics/{exercise}.yaml:") and "must be a" in p for p in problems
    ), problems


def test_cli_validate_of_random_bytes_prints_path_line(course_copy: Path, tmp_path: Path) -> None:
    _random_yaml(course_copy)
    _control_character(course_copy)
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "SLAMCOURSE_HOME": str(tmp_path)}
    done = subprocess.run(
        [sys.executable, "-m", "slamcourse", "validate", str(course_copy), "--variants", "1"],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert "Traceback" not in done.stderr, done.stderr
    assert done.returncode == 1
    assert "exercises/basics/distance.yaml:1: byte " in done.stdout
    assert "exercises/basics/count.yaml:" in done.stdout


def test_course_folder_that_is_a_symlink_loop_is_a_usage_error(tmp_path: Path) -> None:
    os.symlink("loop", tmp_path / "loop")
    with pytest.raises(UsageError, match="loop: cannot be resolved"):
        course_root(tmp_path / "loop")


def test_chapter_context_of_a_broken_chapter_is_a_course_error(course_copy: Path) -> None:
    engine = Engine(load_course(course_copy), NO_RECORD)
    assert engine.course.problems == []  # indexed while the chapter was readable
    _prose_byte(course_copy)
    with pytest.raises(CourseError, match=r"chapters/01-basics\.md:\d+: byte 0xff"):
        engine.context("basics/heading")


# ------------------------------------------------------------------ 5. canonical in range


@pytest.mark.parametrize(
    ("file", "old", "new", "words"),
    [
        (
            "count.yaml",
            "n: {canonical: 3, int: [1, 50]}",
            "n: {canonical: -5, int: [1, 50]}",
            "parameter 'n': canonical -5 is outside its own range [1, 50]",
        ),
        (
            "count.yaml",
            "n: {canonical: 3, int: [1, 50]}",
            "n: {canonical: 3.5, int: [1, 50]}",
            "parameter 'n': canonical 3.5 must be a whole number",
        ),
        (
            "distance.yaml",
            "dx: {canonical: 3, uniform: [1, 10], round: 1}",
            "dx: {canonical: 30, uniform: [1, 10], round: 1}",
            "parameter 'dx': canonical 30 is outside its own range [1, 10]",
        ),
        (
            "distance.yaml",
            "dx: {canonical: 3, uniform: [1, 10], round: 1}",
            "dx: {canonical: 3, choice: [1, 2]}",
            "parameter 'dx': canonical 3 is not one of its choices [1, 2]",
        ),
        (
            "distance.yaml",
            "dx: {canonical: 3, uniform: [1, 10], round: 1}",
            'dx: {canonical: "4*pi", uniform: [1, 10], round: 1}',
            "parameter 'dx': canonical '4*pi' is 12.5664, outside its own range [1, 10]",
        ),
    ],
)
def test_canonical_outside_its_declared_range(
    course_copy: Path, file: str, old: str, new: str, words: str
) -> None:
    path = course_copy / "exercises/basics" / file
    line = _line_of(path, old.encode())
    path.write_text(path.read_text().replace(old, new, 1))
    ex_id = f"basics/{file.removesuffix('.yaml')}"
    problems = [str(p) for p in validate_exercise(load_course(course_copy), ex_id, 1)]
    assert any(p.startswith(f"exercises/basics/{file}:{line}: {words}") for p in problems)
