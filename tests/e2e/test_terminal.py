"""End to end: the real `slamcourse next` in a pseudo-terminal, driven like a learner."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pexpect
import pytest

from tests.conftest import FIXTURE_COURSE

pytestmark = pytest.mark.e2e


def spawn(home: Path, *args: str) -> pexpect.spawn:
    env = dict(os.environ, NO_COLOR="1", TERM="dumb", COLUMNS="100", SLAMCOURSE_HOME=str(home))
    return pexpect.spawn(
        sys.executable, ["-m", "slamcourse", *args], env=env, encoding="utf-8", timeout=30
    )


def test_next_on_fixture_course(private_home: Path) -> None:
    child = spawn(private_home, "--course", str(FIXTURE_COURSE), "next")
    child.expect_exact("A distance")
    child.expect_exact("answer> ")
    child.sendline("three")
    child.expect_exact("unreadable")
    child.expect_exact("(no attempt counted)")
    child.sendline("1e6")
    child.expect_exact("not yet")
    child.sendline(":hint")
    child.expect_exact("hint 1/2")
    child.expect_exact("Pythagoras.")
    child.expect_exact("answer> ")
    child.sendline(":giveup")
    child.expect_exact("Explanation")
    child.expect_exact("Enter for the next exercise")
    child.sendline("")
    child.expect_exact("Angles are in radians")  # the chapter prose leading to it...
    child.expect_exact("A heading")  # ...then the exercise
    child.sendline("-1")  # the heading of a point with dx, dy > 0 is in (0, π/2): always wrong
    child.expect_exact("✗ not yet")
    child.sendline(":skip")
    child.expect_exact("A count")
    child.sendline(":quit")
    child.expect_exact("Progress saved")
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0
    # the next session resumes where the learner left off
    again = spawn(private_home, "--course", str(FIXTURE_COURSE), "next")
    again.expect_exact("A count")
    again.sendeof()
    again.expect(pexpect.EOF)
    again.close()
    assert again.exitstatus == 0


def test_next_on_bundled_course_solves_first_exercise(private_home: Path) -> None:
    child = spawn(private_home, "next")
    child.expect_exact("exercise 1 of")
    child.expect(r"\[(state/[a-z0-9-]+)\]")
    exercise_id = child.match.group(1)
    child.expect_exact("answer> ")
    # ask the engine for the learner's own correct answer, as a learner with pen and paper would
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    with Engine.open(Settings.from_env(home=private_home)) as engine:
        spec = engine.exercise(exercise_id)
        from slamcourse.kinds import get_kind

        variant = engine.variant(exercise_id)
        answer = get_kind(spec.kind).expected(spec, variant)
    child.sendline(str(answer if not isinstance(answer, list) else " ".join(map(str, answer))))
    child.expect_exact("✓ passed")
    child.expect_exact("Enter for the next exercise")
    child.sendline(":quit")
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0


def test_code_exercise_in_next(private_home: Path) -> None:
    from slamcourse.cli import main

    assert main(["--course", str(FIXTURE_COURSE), "goto", "basics/range-bearing"]) == 0
    child = spawn(private_home, "--course", str(FIXTURE_COURSE), "next", "--no-context")
    child.expect_exact("Write range_bearing")
    child.expect(r"Your file: (\S+\.py)")
    path = Path(child.match.group(1))
    assert path.is_file() and "NotImplementedError" in path.read_text()
    child.expect_exact("check> ")
    child.sendline("")
    child.expect_exact("NotImplementedError")
    child.expect_exact("range_bearing.py:6")
    child.expect_exact("check> ")
    path.write_text(
        "import math\n\ndef range_bearing(dx, dy, theta):\n"
        "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
    )
    child.sendline("")
    child.expect_exact("✓ passed")
    child.expect_exact("Enter for the next exercise")
    child.sendline(":quit")
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0
    # the learner's file is never overwritten by a later `next`
    again = spawn(private_home, "--course", str(FIXTURE_COURSE), "goto", "basics/range-bearing")
    again.expect(pexpect.EOF)
    assert "math.hypot" in path.read_text()


def test_watch_regrades_on_save(private_home: Path) -> None:
    child = spawn(private_home, "--course", str(FIXTURE_COURSE), "watch", "basics/range-bearing")
    child.expect(r"Watching (\S+\.py)")
    path = Path(child.match.group(1))
    child.expect_exact("NotImplementedError")  # the starter, graded at once
    path.write_text(
        "import math\n\ndef range_bearing(dx, dy, theta):\n"
        "    return dx * dx + dy * dy, math.atan2(dy, dx) - theta\n"
    )
    child.expect(r"changed \((inotify|changed)\)")
    child.expect_exact("squared range")  # the misconception, named
    path.write_text(
        "import math\n\ndef range_bearing(dx, dy, theta):\n"
        "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
    )
    child.expect_exact("✓ passed")
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0
