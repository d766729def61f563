"""Mutants, correct variants and shipped recordings of code exercises, on the fixture course.

``validate`` grades every mutant and variant through the real sandbox and reports each one that
goes the wrong way as ``path:line``; shipped recordings make the first check replay, and a stale
one is ignored and reported; ``hidden_seed`` runs extra inputs for a batch grader.
"""

from __future__ import annotations

import json
from pathlib import Path

from slamcourse.course.loader import load_course
from slamcourse.grading import replay, testset
from slamcourse.grading.properties import exercise_seed
from slamcourse.kinds import get_kind
from slamcourse.validate import validate_exercise
from tests.conftest import FIXTURE_COURSE

EXERCISE = "basics/range-bearing"
SOLUTION = (FIXTURE_COURSE / "exercises/basics/solutions/range_bearing.py").read_text()
WRONG = "import math\ndef range_bearing(dx, dy, theta):\n    return math.hypot(dx, dy), 0.0\n"


def write(folder: Path, name: str, text: str) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_text(text)


def problems(course: Path, **options: int | bool) -> list[str]:
    found = validate_exercise(load_course(course), EXERCISE, 0, **options)  # type: ignore[arg-type]
    return [str(p) for p in found]


def test_mutants_that_pass_and_variants_that_fail_are_reported(course_copy: Path) -> None:
    mutants = course_copy / "exercises/basics/mutants/range-bearing"
    variants = course_copy / "exercises/basics/variants/range-bearing"
    write(mutants, "a_passes.py", "# mistake: none really, this is the solution\n" + SOLUTION)
    write(mutants, "b_no_heading.py", "# mistake: ignores the heading\n" + WRONG)
    write(mutants, "c_no_comment.py", WRONG)
    write(variants, "a_fails.py", "# method: claims to be right\n" + WRONG)
    write(
        variants,
        "b_complex.py",
        "# method: complex numbers\nimport cmath\n"
        "def range_bearing(dx, dy, theta):\n"
        "    z = complex(dx, dy) * cmath.exp(-1j * theta)\n    return abs(z), cmath.phase(z)\n",
    )
    found = problems(course_copy, min_mutants=4, min_variants=2)
    assert found[0] == (
        "exercises/basics/range-bearing.yaml:1: 3 mutants in exercises/basics/mutants/"
        "range-bearing/, at least 4 needed: add plausible wrong implementations there "
        "(see docs/authoring.md, 'Mutants and variants')"
    )
    assert found[1] == (
        "exercises/basics/mutants/range-bearing/c_no_comment.py:1: the first line of a mutant "
        "must be '# mistake: <the plausible mistake>'"
    )
    assert (
        "exercises/basics/mutants/range-bearing/a_passes.py:1: this mutant passes every test "
        "input (none really, this is the solution); add an edge example to the exercise's "
        "'examples' where it goes wrong"
    ) in found
    assert (
        "exercises/basics/variants/range-bearing/a_fails.py:1: this correct variant (claims to "
        "be right) fails: Wrong result for `range_bearing(dx=-1, dy=0, theta=0)`: expected "
        "`[1, 3.1416]`, got `[1, 0]`. Value 2 of the tuple: expected 3.1416 (mod 2π), got 0."
    ) in found  # the feedback's first line (the first failing input: the second example)
    # the wrong mutants fail, the complex variant passes, 2 variants are enough
    assert len(found) == 4, found


def test_shipped_recording_is_checked_and_rewritten(course_copy: Path) -> None:
    shipped = course_copy / "exercises/basics/recordings/range-bearing.json"
    yaml = course_copy / "exercises/basics/range-bearing.yaml"
    yaml.write_text(
        yaml.read_text().replace(
            "  - {dx: -1, dy: 0, theta: 0}\n", "  - {dx: -2, dy: 0, theta: 0}\n"
        )
    )
    assert problems(course_copy, min_mutants=0, min_variants=0) == [
        "exercises/basics/recordings/range-bearing.json:1: this recording is stale (it was "
        "drawn for another version of the exercise, its reference.py, the grader or "
        "Hypothesis) and is ignored; run `slamcourse validate --record` to write it"
    ]
    assert problems(course_copy, min_mutants=0, min_variants=0, record=True) == []
    assert json.loads(shipped.read_text())["inputs"][1] == {"dx": -2, "dy": 0, "theta": 0}
    spec = load_course(course_copy).exercise(EXERCISE)
    assert replay.shipped_state(spec, exercise_seed(spec.id)) == "ok"
    shipped.unlink()
    assert problems(course_copy, min_mutants=0, min_variants=0) == [
        "exercises/basics/range-bearing.yaml:1: no recording of test inputs (exercises/basics/"
        "recordings/range-bearing.json), so a learner's first check runs Hypothesis; run "
        "`slamcourse validate --record` to write it"
    ]


def test_first_check_replays_the_shipped_recording(private_home: Path) -> None:
    """A fresh home: the shipped recording decides; nothing is drawn, nothing cached."""
    spec = load_course(FIXTURE_COURSE).exercise(EXERCISE)
    assert replay.shipped_state(spec, exercise_seed(spec.id)) == "ok"
    verdict = get_kind("code").check_source(spec, SOLUTION, "mine.py")  # type: ignore[attr-defined]
    # the test set: the examples, the boundary inputs derived from them and the first recorded
    # inputs, and the recorded inputs (each distinct input once); all of it from the recording
    tests = testset.build(spec)
    recorded = replay.load_shipped(spec, exercise_seed(spec.id))
    assert tests.recorded and recorded is not None
    drawn = {testset.input_key(c.kwargs) for c in tests.cases if c.origin == "drawn"}
    assert drawn and drawn <= {testset.input_key(i) for i in recorded}
    assert verdict.passed and verdict.details["examples"] == len(tests.cases)
    assert not (private_home / "cache" / "inputs").exists()
    wrong = get_kind("code").check_source(spec, WRONG, "mine.py")  # type: ignore[attr-defined]
    assert wrong.status == "failed"
    assert "fixed edge cases" in wrong.feedback or "shrank the failure" in wrong.feedback


def test_a_stale_shipped_recording_is_ignored_at_check_time(course_copy: Path) -> None:
    shipped = course_copy / "exercises/basics/recordings/range-bearing.json"
    data = json.loads(shipped.read_text())
    data["key"] = "0" * 64
    data["inputs"] = [{"dx": 1e-300, "dy": 0, "theta": 0}]  # would fail a correct function
    shipped.write_text(json.dumps(data))
    spec = load_course(course_copy).exercise(EXERCISE)
    assert replay.load_shipped(spec, exercise_seed(spec.id)) is None
    verdict = get_kind("code").check_source(spec, SOLUTION, "mine.py")  # type: ignore[attr-defined]
    assert verdict.passed
    # the check drew its inputs afresh (and cached them for the next check): the test set
    # built from that cache is the one it ran, without the stale recording's input
    tests = testset.build(spec)
    assert tests.recorded  # (from that cache)
    assert verdict.details["examples"] == len(tests.cases)
    stale = testset.input_key(data["inputs"][0])
    assert all(testset.input_key(c.kwargs) != stale for c in tests.cases)


def test_hidden_seed_runs_inputs_no_recording_holds() -> None:
    """A function that is right on exactly the inputs a learner's check uses passes the
    ordinary check and fails the hidden one (grading mode)."""
    spec = load_course(FIXTURE_COURSE).exercise(EXERCISE)
    # what a learner's check runs: the examples, the boundary inputs and the recorded inputs
    visible = testset.build(spec).visible
    assert any(c.origin.startswith("boundary") for c in visible)
    known = sorted(
        {(float(c.kwargs["dx"]), float(c.kwargs["dy"]), float(c.kwargs["theta"])) for c in visible}
    )
    memoriser = (
        f"import math\nKNOWN = set({known!r})\n"
        "def range_bearing(dx, dy, theta):\n"
        "    bearing = math.atan2(dy, dx) - theta\n"
        "    if (float(dx), float(dy), float(theta)) not in KNOWN:\n"
        "        bearing += 1.0\n"
        "    return math.hypot(dx, dy), bearing\n"
    )
    kind = get_kind("code")
    assert kind.check_source(spec, memoriser, "m.py").passed  # type: ignore[attr-defined]
    hidden = kind.check_source(spec, memoriser, "m.py", hidden_seed=12345)  # type: ignore[attr-defined]
    assert hidden.status == "failed" and hidden.details["hidden"] is True
    assert "the hidden checks drew" in hidden.feedback
    honest = kind.check_source(spec, SOLUTION, "m.py", hidden_seed=12345)  # type: ignore[attr-defined]
    # every input the hidden run drew, less those drawn twice or already visible (kept once)
    hidden_cases = [c for c in testset.build(spec, hidden_seeds=[12345]).cases if c.hidden]
    assert honest.passed and honest.details["hidden_examples"] == len(hidden_cases) > 0
    assert "12345" not in json.dumps([honest.details, hidden.details])  # the secret stays secret


def test_hypothesis_version_is_read_without_importlib_metadata() -> None:
    from importlib.metadata import version

    assert replay.hypothesis_version() == version("hypothesis")
