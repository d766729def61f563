"""End to end: the real `slamcourse next` in a pseudo-terminal, driven like a learner."""

from __future__ import annotations

import io
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
    child.logfile_read = log = io.StringIO()
    child.expect(r"Watching (\S+\.py)")
    path = Path(child.match.group(1))
    child.expect_exact("`slamcourse hint basics/range-bearing` in another terminal")
    child.expect_exact("NotImplementedError")  # the starter, graded at once
    path.write_text(
        "import math\n\ndef range_bearing(dx, dy, theta):\n"
        "    return dx * dx + dy * dy, math.atan2(dy, dx) - theta\n"
    )
    # in the learner's words, not the mechanism's ("changed (inotify)")
    child.expect_exact("range_bearing.py saved; checking again…")
    child.expect_exact("squared range")  # the misconception, named
    # the second miss nudges towards the hints with a command watch's terminal can run (watch
    # reads no `:hint`)
    child.expect_exact("Stuck? A hint is available.")
    child.expect(r"Type `([^`]*)`")
    assert child.match.group(1) == "slamcourse hint basics/range-bearing"
    path.write_text(
        "import math\n\ndef range_bearing(dx, dy, theta):\n"
        "    return math.hypot(dx, dy), math.atan2(dy, dx) - theta\n"
    )
    child.expect_exact("✓ passed")
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0
    assert "inotify" not in log.getvalue() and ":hint" not in log.getvalue()


def _fixture_engine(home: Path):  # type: ignore[no-untyped-def]
    from slamcourse.engine import Engine
    from slamcourse.settings import Settings

    return Engine.open(Settings.from_env(course=FIXTURE_COURSE, home=home))


def test_goto_a_solved_exercise_says_so_and_next_poses_it(private_home: Path) -> None:
    with _fixture_engine(private_home) as engine:
        assert engine.submit("basics/bug", "3").passed
    goto = spawn(private_home, "--course", str(FIXTURE_COURSE), "goto", "basics/bug")
    goto.expect_exact("`slamcourse next` will pose basics/bug.")
    goto.expect_exact("already solved", timeout=10)
    goto.expect(pexpect.EOF)
    child = spawn(private_home, "--course", str(FIXTURE_COURSE), "next", "--no-context")
    child.expect_exact("already solved", timeout=10)
    child.expect_exact("Find the bug", timeout=10)  # what goto said: the solved exercise
    child.expect_exact("answer> ")
    child.sendline("3")
    child.expect_exact("✓ passed")
    child.expect_exact("Enter for the next exercise")
    child.sendline("")
    child.expect_exact("Write range_bearing", timeout=10)  # then on from it, in its chapter
    child.expect_exact("check> ")
    child.sendline(":quit")
    child.expect(pexpect.EOF)


def test_next_says_which_skipped_exercises_it_passes_over(private_home: Path) -> None:
    with _fixture_engine(private_home) as engine:
        engine.skip("basics/distance")
        engine.give_up("boundaries/read-edges")  # the last one: next wraps, past the skipped
    child = spawn(private_home, "--course", str(FIXTURE_COURSE), "next", "--no-context")
    child.expect_exact("Passing over 1 skipped exercise: `basics/distance`.", timeout=10)
    child.expect_exact("back to the earliest open one, `basics/heading`.", timeout=10)
    child.expect_exact("A heading")
    child.expect_exact("answer> ")
    child.sendline(":skip")
    child.expect_exact("`next` comes back to it when the rest are done", timeout=10)
    child.expect_exact("A count")
    child.sendline(":quit")
    child.expect(pexpect.EOF)


def test_list_marks_have_a_legend(private_home: Path) -> None:
    with _fixture_engine(private_home) as engine:
        assert engine.submit("basics/bug", "3").passed
        engine.give_up("basics/count")
        engine.skip("basics/heading")
    child = spawn(private_home, "--course", str(FIXTURE_COURSE), "list")
    child.expect(r"↷ basics/heading\s+A heading", timeout=10)
    child.expect(r"⚐ basics/count\s+A count", timeout=10)  # given up: the browser's mark too
    child.expect(r"✓ basics/bug\s+Find the bug\r\n", timeout=10)
    child.expect_exact("✓ solved   ⚐ given up   ○ open   ↷ skipped   ← next:", timeout=10)
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0
