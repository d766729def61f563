"""The notebook face in process: what show/check/hint/explain/progress return and display, on
the engine's rules, and what it writes into a notebook's output metadata."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from slamcourse.engine import Engine
from slamcourse.notebook.cells import answer_text, check_calls, code_answer
from slamcourse.notebook.views import ExerciseView, Notice, ResultView
from tests.conftest import REPO
from tests.notebook.conftest import CODE_ID, SOLUTION, right_answer


def _bundle(view: Any) -> tuple[dict[str, str], dict[str, Any]]:
    data, meta = view._repr_mimebundle_()
    assert set(data) == {"text/html", "text/plain"}
    return data, meta["slamcourse"]


def test_show_poses_the_learners_own_variant_with_math_for_mathjax(nb: Any, engine: Engine) -> None:
    view = nb.show("basics/distance")
    assert isinstance(view, ExerciseView)
    prompt = engine.pose("basics/distance")
    data, meta = _bundle(view)
    # the prompt's math reaches the page as $…$ text for the notebook's MathJax
    assert "$(" in data["text/html"] and 'class="math' not in data["text/html"]
    assert "check(&quot;basics/distance&quot;" in data["text/html"]
    # the plain text is the terminal's rendering: Unicode math, no dollars
    assert "$" not in data["text/plain"] and prompt.title in data["text/plain"]
    assert meta["exercise"] == "basics/distance" and meta["variant"] == prompt.variant.seed
    assert meta["learner"]["seed"] == engine.progress.learner_seed  # type: ignore[union-attr]
    assert meta["course"]["hash"].startswith("sha256:")
    practice = nb.show("basics/distance", canonical=True)
    assert practice.prompt.practice and "practice" in practice._repr_html_()


def test_show_lists_options_code_and_listings(nb: Any) -> None:
    pick = nb.show("basics/pick")._repr_html_()
    assert "A pose graph optimiser" in pick and "sc-options" in pick
    code = nb.show(CODE_ID)
    assert "%%slamcourse check basics/range-bearing" in code._repr_html_()
    assert "range_bearing(dx, dy, theta)" in repr(code)
    bug = nb.show("basics/bug")._repr_html_()
    assert "def distance(dx, dy):" in bug


def test_check_right_and_wrong_answers_follow_the_engines_rules(nb: Any, engine: Engine) -> None:
    wrong = nb.check("basics/count", "1")
    assert isinstance(wrong, ResultView) and wrong.status == "failed"
    assert wrong.result.counted and engine.state("basics/count").attempts == 1
    assert "✗ Not yet" in repr(wrong)
    unreadable = nb.check("basics/count", "three")
    assert unreadable.status == "invalid" and "(no attempt counted)" in repr(unreadable)
    assert engine.state("basics/count").attempts == 1
    right = nb.check("basics/count", int(right_answer(engine, "basics/count")))
    data, meta = _bundle(right)
    assert right.passed and "Explanation" in data["text/html"]
    assert meta["answer"] == right_answer(engine, "basics/count")
    assert meta["status"] == "passed"
    assert engine.state("basics/count").status == "solved"


def test_values_are_written_out_in_full(nb: Any, engine: Engine) -> None:
    value = np.array(eval(right_answer(engine, "basics/offset")), dtype=float)
    assert nb.check("basics/offset", value).passed
    matrix = np.eye(2)
    assert nb.check("basics/identity", matrix).passed
    assert answer_text(np.float64(0.1) + 0.2) == "0.30000000000000004"
    assert answer_text(["a", "c"]) == "a, c"
    assert answer_text(None) is None and answer_text(...) is None
    assert answer_text([[1, 0], [0, 1]]) == "[[1, 0], [0, 1]]"
    none = nb.check("basics/count", None)
    assert isinstance(none, Notice) and "No answer yet" in repr(none)


def test_code_by_source_and_by_function(nb: Any, tmp_path: Path) -> None:
    ok = nb.check(CODE_ID, SOLUTION)
    assert ok.passed
    _, meta = _bundle(ok)
    assert meta["source"] == SOLUTION  # what a handed-in notebook is graded on
    # a function defined in a notebook: its source, with the imports and helpers it uses
    module = tmp_path / "cells.py"
    module.write_text(
        textwrap.dedent(
            """
            import math as m
            import numpy as np

            OFFSET = 0.0

            def _rng(dx, dy):
                return float(np.hypot(dx, dy))

            def mine(dx, dy, theta):
                return _rng(dx, dy), m.atan2(dy, dx) - theta + OFFSET

            def forgets_heading(dx, dy, theta):
                return _rng(dx, dy), m.atan2(dy, dx)
            """
        )
    )
    spec = importlib.util.spec_from_file_location("cells_under_test", module)
    assert spec is not None and spec.loader is not None
    cells = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cells)
    source = nb.function_source(cells.mine, nb.engine().exercise(CODE_ID))
    assert "import math as m" in source and "def _rng" in source and "OFFSET = 0.0" in source
    assert source.rstrip().endswith("range_bearing = mine")
    assert nb.check(CODE_ID, cells.mine).passed
    wrong = nb.check(CODE_ID, cells.forgets_heading)
    assert wrong.status == "failed" and wrong.result.tests[0]["input"] is not None
    assert "<table" in wrong._repr_html_()
    assert isinstance(nb.check(CODE_ID, lambda dx, dy, theta: (0, 0)), Notice)
    assert isinstance(nb.check(CODE_ID, 42), Notice)


def test_help_and_mistakes_are_shown_never_raised(nb: Any, engine: Engine) -> None:
    locked = nb.explain("basics/distance")
    assert isinstance(locked, Notice) and "not solved yet" in repr(locked)
    first = nb.hint("basics/distance")
    assert "Hint 1 of 2" in repr(first) and engine.state("basics/distance").hints_shown == 1
    assert "$" in nb.hint("basics/distance")._repr_html_()  # the second hint is math
    assert "No more hints" in repr(nb.hint("basics/distance"))
    gave_up = nb.give_up("basics/distance")
    assert "Explanation" in repr(gave_up) and engine.state("basics/distance").status == "given_up"
    assert "Explanation" in repr(nb.explain("basics/distance"))
    assert isinstance(nb.show("no/such"), Notice)
    assert isinstance(nb.check("no/such", "1"), Notice)
    assert isinstance(nb.progress("no-such-chapter"), Notice)
    progress = nb.progress("basics")
    text = repr(progress)
    assert "⚐ basics/distance" in text and "0/15 solved" in text
    assert _bundle(progress)[1]["learner"]["seed"] == engine.progress.learner_seed  # type: ignore[union-attr]
    every = repr(nb.progress())
    assert " 1. Fixture basics  0/11" in every and " 2. " in every


def test_cell_conventions() -> None:
    cell = "%%slamcourse check basics/range-bearing\nimport math\n"
    found = code_answer(cell)
    assert found is not None and found.exercise == CODE_ID and found.source == "import math\n"
    assert code_answer("%%slamcourse show x\n") is None and code_answer("import math") is None
    calls = check_calls(
        '%time x = 1\ncheck("a/b", "7/5")\nr = check("a/c", [1, 2.5])\n'
        'check("a/d", np.pi / 4)\ncheck("a/e", "")\nprint(check)\n'
    )
    assert [(c.exercise, c.text, c.expression, c.empty) for c in calls] == [
        ("a/b", "7/5", '"7/5"', False),
        ("a/c", "[1, 2.5]", "[1, 2.5]", False),
        ("a/d", None, "np.pi / 4", False),
        ("a/e", "", '""', True),
    ]
    assert check_calls("def broken(:\n") == []


def test_the_core_imports_no_jupyter() -> None:
    code = (
        "import sys\n"
        "import slamcourse.cli, slamcourse.engine, slamcourse.batch.grade\n"
        "import slamcourse.notebook, slamcourse.notebook.export, slamcourse.notebook.hub\n"
        "import slamcourse.web.app\n"
        "bad = [m for m in ('IPython', 'nbformat', 'nbclient', 'jupyter_server', 'ipykernel')"
        " if m in sys.modules]\n"
        "assert not bad, bad\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=REPO)
