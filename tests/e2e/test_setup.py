"""The README's first command, as a newcomer runs it: afterwards a new shell finds `slamcourse`."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from tests.conftest import REPO

pytestmark = pytest.mark.e2e


def test_start_script_puts_slamcourse_on_the_path_of_a_new_shell(tmp_path: Path) -> None:
    home = tmp_path / "user"
    home.mkdir()
    env = {k: v for k, v in os.environ.items() if not k.startswith("SLAMCOURSE_")}
    env.update(HOME=str(home), NO_COLOR="1", TERM="dumb")
    started = subprocess.run(
        ["bash", str(REPO / "scripts" / "start.sh")],
        env=env,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert started.returncode == 0, started.stderr
    assert "exercise 1 of" in started.stdout  # it started the course
    # a new interactive shell with a plain PATH, as a terminal opened afterwards would have
    fresh = {"HOME": str(home), "PATH": "/usr/bin:/bin", "TERM": "dumb"}
    shell = subprocess.run(
        ["bash", "-i", "-c", "command -v slamcourse && slamcourse status"],
        env=fresh,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert shell.returncode == 0, shell.stderr
    assert shell.stdout.startswith(str(home / ".local" / "bin" / "slamcourse"))
    assert "Overall: 0/" in shell.stdout
    # running it again changes nothing in the shell files and skips pip
    again = subprocess.run(
        ["bash", str(REPO / "scripts" / "start.sh")],
        env=env,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert again.returncode == 0 and "pip install" not in again.stderr
    assert (home / ".bashrc").read_text().count("slamcourse: ~/.local/bin on PATH") == 1
