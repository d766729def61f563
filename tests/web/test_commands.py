"""`slamcourse serve` and `slamcourse plot` as commands."""

from __future__ import annotations

import os
import subprocess
import sys
import urllib.error
import urllib.request
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from slamcourse.cli import main
from tests.conftest import FIXTURE_COURSE, REPO


def test_plot_writes_the_learners_picture(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "range.svg"
    course = ["--course", str(REPO)]
    assert main([*course, "plot", "observation/predicted-range", "--out", str(out)]) == 0
    root = ET.fromstring(out.read_text())
    assert root.find("{http://www.w3.org/2000/svg}desc") is not None
    assert "r = ?" in out.read_text()  # open exercise: its answer is not drawn
    assert "Wrote the picture" in capsys.readouterr().out
    # a picture that shows the answer comes once the exercise is given up (or solved)
    drift = [*course, "plot", "drift/systematic-drift", "--out", str(out)]
    assert main(drift) == 2
    assert "once the exercise is solved or given up" in capsys.readouterr().err
    assert main([*course, "giveup", "drift/systematic-drift"]) == 0
    assert main(drift) == 0
    assert "believed" in out.read_text()


def test_plot_of_an_exercise_without_one(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--course", str(REPO), "plot", "state/why-dense"]) == 2
    err = capsys.readouterr().err
    assert "has no picture" in err and "drift/systematic-drift" in err


def test_serve_prints_a_tokened_address_and_serves_it(tmp_path: Path) -> None:
    env = dict(
        os.environ,
        SLAMCOURSE_HOME=str(tmp_path / "home"),
        PYTHONPATH=str(REPO / "src"),
        PYTHONUNBUFFERED="1",
    )
    cmd = [sys.executable, "-m", "slamcourse", "--course", str(FIXTURE_COURSE), "serve"]
    proc = subprocess.Popen(
        [*cmd, "--no-browser", "--port", "0"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        assert proc.stdout is not None
        url = ""
        for _ in range(5):
            line = proc.stdout.readline()
            if "?token=" in line:
                url = line.strip()
                break
        assert url.startswith("http://127.0.0.1:")
        base = url.split("?")[0]
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(base + "chapter/basics", timeout=10)
        assert refused.value.code == 403
        refused.value.close()
        opener = urllib.request.build_opener(urllib.request.HTTPCookieProcessor())
        with opener.open(url, timeout=10) as page:
            assert page.status == 200
            assert "Fixture basics" in page.read().decode()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
        if proc.stdout is not None:
            proc.stdout.close()
