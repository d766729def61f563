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


def _installed_copy(tmp_path: Path) -> Path:
    """The repository's scripts and pyproject.toml beside the repository's own venv, stamped
    as installed from that pyproject: `setup.sh` then has nothing to install."""
    import hashlib
    import shutil

    root = tmp_path / "clone"
    (root / "scripts").mkdir(parents=True)
    for name in ("start.sh", "setup.sh"):
        shutil.copy(REPO / "scripts" / name, root / "scripts" / name)
    shutil.copy(REPO / "pyproject.toml", root / "pyproject.toml")
    (root / ".venv").mkdir()
    (root / ".venv" / "bin").symlink_to(REPO / ".venv" / "bin", target_is_directory=True)
    digest = hashlib.sha256((root / "pyproject.toml").read_bytes()).hexdigest()
    (root / ".venv" / ".slamcourse-installed").write_text(digest + "\n")
    return root


@pytest.mark.parametrize(("args", "expected"), [(["status"], "Overall: 0/"), (["list"], "state/")])
def test_start_script_runs_the_command_it_is_given(
    tmp_path: Path, args: list[str], expected: str
) -> None:
    """`bash scripts/start.sh status` runs `slamcourse status` (it used to run `next status`,
    which fails), with the venv as installed: no pip, no apt."""
    root = _installed_copy(tmp_path)
    home = tmp_path / "user"
    home.mkdir()
    env = {k: v for k, v in os.environ.items() if not k.startswith("SLAMCOURSE_")}
    env.update(
        HOME=str(home), NO_COLOR="1", TERM="dumb", SLAMCOURSE_HOME=str(tmp_path / "progress")
    )
    ran = subprocess.run(
        ["bash", str(root / "scripts" / "start.sh"), *args],
        env=env,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert ran.returncode == 0, ran.stderr
    assert "pip install" not in ran.stderr and "apt-get" not in ran.stderr  # nothing reinstalled
    assert expected in ran.stdout
    assert "answer>" not in ran.stdout  # not `next`
