"""Golden text of a few complete terminal screens, so wording regressions show in review.

Regenerate after an intended change with ``SLAMCOURSE_UPDATE_GOLDEN=1 pytest tests/e2e/
test_golden_screens.py`` and read the diff.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from slamcourse.cli import main
from tests.conftest import FIXTURE_COURSE

GOLDEN = Path(__file__).parent / "golden"

WRONG_RANGE = """\
import math

def range_bearing(dx, dy, theta):
    return dx * dx + dy * dy, math.atan2(dy, dx) - theta
"""

SCREENS: dict[str, list[str]] = {
    "prompt": ["show", "observation/predicted-bearing", "--canonical"],
    "misconception": [
        "check",
        "observation/predicted-bearing",
        "--canonical",
        "--answer",
        "atan2(4, 3)",
    ],
    "unreadable": ["check", "observation/innovation", "--canonical", "--answer", "-0.09"],
    "code-failure": [
        "--course",
        str(FIXTURE_COURSE),
        "check",
        "basics/range-bearing",
        "--file",
        "{wrong}",
    ],
}


@pytest.mark.parametrize("name", sorted(SCREENS))
def test_screen_matches_its_golden_text(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("COLUMNS", "100")
    wrong = tmp_path / "range_bearing.py"
    wrong.write_text(WRONG_RANGE)
    main([arg.replace("{wrong}", str(wrong)) for arg in SCREENS[name]])
    screen = capsys.readouterr().out
    golden = GOLDEN / f"{name}.txt"
    if os.environ.get("SLAMCOURSE_UPDATE_GOLDEN"):
        golden.write_text(screen, encoding="utf-8")
    assert screen == golden.read_text(encoding="utf-8")
