"""The engine is the one boundary: faces render what it returns and hold no rule of their own."""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from slamcourse.cli import join_option_values, main
from slamcourse.engine import Engine
from slamcourse.settings import Settings
from tests.conftest import FIXTURE_COURSE, REPO

CLI = REPO / "src" / "slamcourse" / "cli.py"


def _imported_modules(path: Path) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
        elif isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
    return names


def test_cli_imports_nothing_from_the_sandbox_or_the_grader() -> None:
    imported = _imported_modules(CLI)
    assert not {m for m in imported if m.startswith(("slamcourse.sandbox", "slamcourse.grading"))}
    assert not {m for m in imported if m.startswith("slamcourse.kinds")}


def test_settings_are_read_from_the_environment_in_one_place() -> None:
    env = {"SLAMCOURSE_HOME": "/h", "SLAMCOURSE_WORKSPACE": "/w", "SLAMCOURSE_COURSE": "/c"}
    s = Settings.from_env(env)
    assert (s.home, s.workspace, s.course) == (Path("/h"), Path("/w"), Path("/c"))
    assert Settings.from_env({"SLAMCOURSE_HOME": "/h"}).workspace == Path("/h/workspace")
    explicit = Settings.from_env(env, course="/other", require_isolation=True, record=False)
    assert explicit.course == Path("/other") and explicit.require_isolation and not explicit.record


def test_answers_starting_with_a_dash_reach_the_checker() -> None:
    assert join_option_values(["check", "x", "--answer", "-dx/sqrt(q)"]) == [
        "check",
        "x",
        "--answer=-dx/sqrt(q)",
    ]
    assert join_option_values(["check", "x", "--answer"]) == ["check", "x", "--answer"]
    assert join_option_values(["--answer=-1"]) == ["--answer=-1"]


@pytest.mark.parametrize("answer", ["-dx", "-3 -4", "-1e9", "--5"])
def test_cli_grades_dash_answers_instead_of_a_usage_error(
    answer: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["--course", str(FIXTURE_COURSE), "check", "basics/offset", "--answer", answer])
    assert code in (0, 1), capsys.readouterr().err  # graded (or unreadable), never exit 2
    assert "expected one argument" not in capsys.readouterr().err


def test_result_and_prompt_are_json_data(tmp_path: Path) -> None:
    settings = Settings(home=tmp_path, workspace=tmp_path / "ws", course=FIXTURE_COURSE)
    with Engine.open(settings) as engine:
        data = engine.submit("basics/offset", "[0, 0]").to_dict()
        assert json.loads(json.dumps(data)) == data
        assert data["status"] == "failed" and data["counted"] and data["explanation"] is None
        assert data["details"]["wrong"]  # wrong entries, for a face to mark
        code = engine.submit_code("basics/range-bearing", source="def range_bearing(a, b, c):\n")
        assert code.verdict.status == "invalid"  # a syntax error costs no attempt
        prompt = engine.pose("basics/range-bearing").to_dict()
        assert prompt["form"]["type"] == "code" and prompt["form"]["file"].endswith(".py")
        assert "def range_bearing" in prompt["form"]["starter"]
        assert json.loads(json.dumps(prompt)) == prompt


def test_one_engine_serves_several_threads(tmp_path: Path) -> None:
    settings = Settings(home=tmp_path, workspace=tmp_path / "ws", course=FIXTURE_COURSE)
    errors: list[BaseException] = []
    with Engine.open(settings) as engine:

        def work() -> None:
            try:
                for _ in range(10):
                    engine.submit("basics/distance", "1e9")
                    engine.summary()
            except BaseException as exc:  # pragma: no cover - reported below
                errors.append(exc)

        threads = [threading.Thread(target=work) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert errors == []
        assert engine.state("basics/distance").attempts == 40


def test_piped_output_that_is_cut_short_is_not_a_traceback(private_home: Path) -> None:
    env = dict(os.environ, SLAMCOURSE_HOME=str(private_home))
    command = f"{sys.executable} -m slamcourse list | head -3"
    done = subprocess.run(
        ["bash", "-c", command], env=env, capture_output=True, text=True, timeout=60
    )
    assert len(done.stdout.splitlines()) == 3
    assert "Traceback" not in done.stderr and "BrokenPipe" not in done.stderr
