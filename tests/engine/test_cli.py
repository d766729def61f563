"""The CLI in-process: exit codes, --json shapes, and messages users see."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from slamcourse.cli import main
from tests.conftest import FIXTURE_COURSE

COURSE = ["--course", str(FIXTURE_COURSE)]


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main([*COURSE, *argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_check_exit_codes_and_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "check", "basics/distance", "--answer", "5", "--canonical")
    assert code == 0 and "passed" in out
    code, out, _ = run(
        capsys, "check", "basics/distance", "--answer", "25", "--canonical", "--json"
    )
    data = json.loads(out)
    assert code == 1
    assert data["verdict"]["status"] == "failed"
    assert data["verdict"]["misconception"] == "squared"
    assert data["variant"] == 0
    code, out, _ = run(capsys, "check", "basics/distance", "--answer", "abc", "--canonical")
    assert code == 1 and "no attempt counted" in out
    code, _, err = run(capsys, "check", "basics/distanse", "--answer", "5")
    assert code == 2 and "did you mean 'basics/distance'" in err
    code, _, err = run(capsys, "check", "basics/distance")
    assert code == 2 and "--answer" in err
    assert main(["check"]) == 2


def test_seed_selects_a_variant(capsys: pytest.CaptureFixture[str]) -> None:
    _, out, _ = run(capsys, "show", "basics/distance", "--seed", "3", "--json")
    shown = json.loads(out)
    assert shown["variant"] == 3 and shown["kind"] == "number"
    _, out0, _ = run(capsys, "show", "basics/distance", "--canonical")
    assert "(3, 4)" in out0 and "canonical variant" in out0


def test_progress_commands(capsys: pytest.CaptureFixture[str], private_home: Path) -> None:
    code, _, err = run(capsys, "explain", "basics/count")
    assert code == 2 and "not solved yet" in err
    code, out, _ = run(capsys, "hint", "basics/distance", "--json")
    assert json.loads(out)["hint"] == "Pythagoras."
    run(capsys, "giveup", "basics/count")
    code, out, _ = run(capsys, "explain", "basics/count", "--json")
    assert code == 0 and json.loads(out)["explanation"]
    code, out, _ = run(capsys, "status", "--json")
    status = json.loads(out)
    # next goes on after the exercise just given up (basics/count), in its chapter
    assert status["total"] == 15 and status["next"] == "basics/offset"
    run(capsys, "goto", "basics/bug")
    code, out, _ = run(capsys, "list")
    assert "basics/bug" in out and "← next" in out.split("basics/bug")[1].splitlines()[0]
    code, _, err = run(capsys, "reset")
    assert code == 2 and "--yes" in err
    assert run(capsys, "reset", "--yes")[0] == 0
    assert (private_home / "progress.sqlite3").is_file()


def test_validate_reports_broken_course(
    capsys: pytest.CaptureFixture[str], course_copy: Path
) -> None:
    none = ["--min-mutants", "0", "--min-variants", "0"]  # the fixture ships none
    path = course_copy / "exercises/basics/count.yaml"
    path.write_text(path.read_text().replace("exact: true", "exakt: true"))
    code = main(["validate", str(course_copy), "--variants", "3", *none])
    out = capsys.readouterr().out
    assert code == 1
    assert "exercises/basics/count.yaml:9: unknown key 'exakt'" in out
    assert main(["validate", str(FIXTURE_COURSE), "--variants", "3", *none]) == 0
    assert main(["validate", str(FIXTURE_COURSE), "--variants", "1"]) == 1  # 8/3 by default
    assert "at least 8" in capsys.readouterr().out


def test_corrupt_progress_is_a_clear_error(
    capsys: pytest.CaptureFixture[str], private_home: Path
) -> None:
    db = private_home / "progress.sqlite3"
    db.write_bytes(b"not a database" * 100)
    code, _, err = run(capsys, "status")
    assert code == 5 and str(db) in err and "Move it aside" in err
    assert db.read_bytes() == b"not a database" * 100


def test_bad_course_path(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code = main(["--course", str(tmp_path), "list"])
    assert code == 2 and "is not a course" in capsys.readouterr().err


def test_lazy_parser_knows_every_command() -> None:
    """main() builds only the requested subcommand; its list of names must stay complete."""
    from slamcourse import cli

    full = cli.build_parser()
    names = set(full._subparsers._group_actions[0].choices)  # type: ignore[union-attr]
    assert names == cli._COMMANDS
    assert cli.requested_command(["--course", "x", "--no-color", "show", "a/b"]) == "show"
    assert cli.requested_command(["--help"]) is None
