"""Argument types and their boundary inputs (slamcourse.grading.domains): parsing with lines
and fixes; every class derived, inside the declared domain, deterministic and sendable."""

from __future__ import annotations

import itertools
import math
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.course.loader import load_course
from slamcourse.course.schema import Checker
from slamcourse.course.yamlio import load_yaml
from slamcourse.errors import CourseError
from slamcourse.grading import domains
from slamcourse.grading.domains import (
    ArgType,
    Derived,
    boundary_classes,
    boundary_inputs,
    parse_mutates,
    parse_types,
    parse_valid,
    representation_classes,
    types_from_arguments,
)
from slamcourse.grading.strategies import Argument
from slamcourse.sandbox.protocol import encode_arg
from tests.conftest import FIXTURE_COURSE, REPO

PI = math.pi

G2O = (
    "VERTEX_SE2 0 0.000000 0.000000 0.000000\n"
    "VERTEX_SE2 1 0.774115 1.183389 1.576173\n"
    "EDGE_SE2 0 1 0.774115 1.183389 1.576173 1.000000 0.000000 0.000000 1.000000 0.000000 "
    "1.000000\n"
    "EDGE_SE2 1 0 -0.5 0.25 3.0 4 0.5 -0.25 9 0.75 100\n"
)

EDGE3 = (
    "EDGE3 0 1 1.08756 0.258927 0.247199 -0.537378 -0.131531 -0.265704 19.564 -1.583 -4.631 "
    "1.516 5.014 -0.7 32.459 -1.456 2.341 9.642 8.743 12.867 0.226 2.206 -0.659 38.736 5.323 "
    "9.934 40.523 -8.54 91.04\n"
    "EDGE3 1 2 0.606173 0.0650451 0.0357494 -0.311014 -0.232185 -0.0832918 16.122 -2.262 0.377 "
    "-0.554 4.169 -4.445 22.312 -6.314 2.935 -6.479 3.453 16.987 3.479 -4.417 -1.587 37.158 "
    "-5.759 8.653 154.698 28.747 74.611\n"
)
ROTATION = [  # 2.5 rad about (1, 2, 3)
    [-0.672490500150724, -0.22253899465722543, 0.7058561631550584],
    [0.7371514562420636, -0.2865311539620954, 0.6119702838940424],
    [0.06606252922219896, 0.9318671008604722, 0.3567344230189523],
]


def parse(text: str, signature: list[str]) -> tuple[tuple[ArgType, ...], Checker]:
    """``types:`` of a YAML text (the key on line 1), as the code kind parses it."""
    raw = load_yaml(text, "ex.yaml")
    check = Checker("ex.yaml")
    types = parse_types(raw["types"], signature, check, line=raw.line_of("types"))
    return types, check


def messages(check: Checker) -> list[str]:
    return [f"{p.line}: {p.message}" for p in check.problems]


# ------------------------------------------------------------------------------ parsing


def test_bare_names_and_mappings_parse_in_signature_order() -> None:
    text = """types:
  b: pose
  a: angle
  n: {type: count, range: [1, 30000]}
  x: {type: real, range: [-50, 50]}
  w: {type: angle, range: [-2*pi, 2*pi], open: low}
  p: probability
  q: {type: probability, range: [0.5, 0.99], open: both}
  P: {type: covariance, size: 3}
  M: {type: matrix, size: [2, 3]}
  z: {type: vector, length: 2, angles: [1]}
  e: {type: edges, ordered: false, ties: true, empty: true}
  t: g2o
  c: choice
"""
    signature = ["a", "b", "n", "x", "w", "p", "q", "P", "M", "z", "e", "t", "c"]
    types, check = parse(text, signature)
    assert check.problems == []
    assert [t.name for t in types] == signature
    by = {t.name: t for t in types}
    assert by["a"].bounds == (-PI, PI) and by["b"].type == "pose"
    assert repr(by["n"].bounds) == "(1, 30000)"  # whole numbers stay ints
    assert by["w"].bounds == (-2 * PI, 2 * PI) and by["w"].open == "low"
    assert by["p"].bounds == (0.0, 1.0) and by["q"].open == "both"
    assert by["P"].size == (3, 3) and by["M"].size == (2, 3)
    assert by["z"].length == 2 and by["z"].angles == (1,)
    assert not by["e"].ordered and by["e"].ties and by["e"].empty
    assert by["t"].line == 13  # each type knows its line


@pytest.mark.parametrize(
    ("body", "signature", "expected"),
    [
        ("  a: angel\n", ["a"], "2: unknown type 'angel' for 'a' (did you mean angle?)"),
        ("  a: angle\n", ["a", "b"], "1: 'types' gives no type for 'b'"),
        ("  a: angle\n  c: real\n", ["a"], "3: 'types' names 'c', which is not a parameter"),
        (
            "  x: {type: real, range: [1]}\n",
            ["x"],
            "2: 'range' of 'x' must be [low, high]: two numbers",
        ),
        ("  x: {type: real, range: [2, 1]}\n", ["x"], "2: 'range' of 'x' must have low < high"),
        ("  x: {type: real, range: [0, tau2]}\n", ["x"], "2: 'range' of 'x' must be [low, high]"),
        ("  n: count\n", ["n"], "2: type 'count' of 'n' needs its range"),
        ("  n: {type: count, range: [0.5, 3]}\n", ["n"], "two whole numbers"),
        (
            "  v:\n    type: vector\n    lenght: 3\n",
            ["v"],
            "4: 'lenght' does not apply to type 'vector' of 'v' (did you mean length?)",
        ),
        ("  x: {type: real, open: left}\n", ["x"], "'open' of 'x' must be one of none, low"),
        ("  P: {type: covariance, size: [2, 3]}\n", ["P"], "'size' of 'P' must be a whole number"),
        ("  p: {type: probability, range: [0, 2]}\n", ["p"], "must lie within [0, 1]"),
        ("  v: {type: vector, length: 2, ties: true}\n", ["v"], "fixed 'length'"),
        ("  v: {type: vector, length: 2, angles: [2]}\n", ["v"], "beyond its length 2"),
        ("  e: {type: edges, ordered: no-thanks}\n", ["e"], "must be true or false"),
        ("  a: {range: [0, 1]}\n", ["a"], "2: the type of 'a' needs 'type: <name>'"),
        ("  a: [angle]\n", ["a"], "2: the type of 'a' must be a type name"),
        ("  t: {type: g2o, range: [0, 1]}\n", ["t"], "it takes no parameters"),
    ],
)
def test_every_mistake_is_a_problem_at_its_line_with_a_fix(
    body: str, signature: list[str], expected: str
) -> None:
    _types, check = parse("types:\n" + body, signature)
    found = messages(check)
    assert any(expected in m for m in found), found


def test_types_that_are_not_a_mapping_are_reported() -> None:
    check = Checker("ex.yaml")
    assert parse_types(["a", "angle"], ["a"], check, line=7) == ()
    assert messages(check)[0].startswith("7: 'types' must map every parameter to its type")


def test_valid_and_mutates_parse() -> None:
    check = Checker("ex.yaml")
    assert parse_valid("landmark_clear", 3, check) == "landmark_clear"
    assert parse_valid(None, 3, check) is None
    assert parse_mutates(["grid"], 4, ["grid", "x"], check) == ("grid",)
    assert parse_mutates("grid", 4, ["grid", "x"], check) == ("grid",)
    assert parse_mutates(None, 4, ["grid"], check) == ()
    assert check.problems == []
    assert parse_valid("not a name", 3, check) is None
    assert parse_mutates(["gird", "grid", "grid"], 4, ["grid", "x"], check) == ("grid",)
    found = messages(check)
    assert found[0].startswith("3: 'valid' must name a function in reference.py")
    assert "4: 'mutates' names 'gird', which is not a parameter (did you mean grid?)" in found[1]
    assert found[2] == "4: 'mutates' names 'grid' twice"


def test_arguments_ranges_give_types_when_none_are_declared() -> None:
    found = types_from_arguments(
        [
            Argument("x", "float", (-20, 20), 1),
            Argument("n", "int", (0, 50), 2),
            Argument("p", "choice", (0.6, 0.9), 3),
        ]
    )
    assert [(t.name, t.type, t.bounds) for t in found] == [
        ("x", "real", (-20.0, 20.0)),
        ("n", "count", (0, 50)),
        ("p", "choice", None),
    ]
    spec = load_course(FIXTURE_COURSE).exercise("basics/range-bearing")
    assert [t.type for t in spec.options.types] == ["real", "real", "real"]


def exercise_problems(course: Path, exercise_id: str) -> list[str]:
    with pytest.raises(CourseError) as caught:
        load_course(course).exercise(exercise_id)
    return [f"{p.path}:{p.line}: {p.message}" for p in caught.value.problems]


def test_the_code_kind_reports_type_mistakes_at_their_line(course_copy: Path) -> None:
    path = course_copy / "exercises" / "boundaries" / "wrap.yaml"
    text = path.read_text()
    text = text.replace("a: {type: angle, range: [-2*pi, 2*pi]}", "a: {type: angel}")
    text = text.replace("  - {a: 4.0}\n", "  - {a: 9.0}\n")
    path.write_text(text + "valid: 12\nmutates: [b]\n")
    lines = text.splitlines()
    problems = exercise_problems(course_copy, "boundaries/wrap")
    where = "exercises/boundaries/wrap.yaml"
    type_line = next(i for i, line in enumerate(lines, 1) if "angel" in line)
    assert any(
        p.startswith(f"{where}:{type_line}: unknown type 'angel' for 'a' (did you mean angle?)")
        for p in problems
    ), problems
    assert any(f"{where}:{len(lines) + 1}: 'valid' must name" in p for p in problems)
    assert any(f"{where}:{len(lines) + 2}: 'mutates' names 'b'" in p for p in problems)


def test_an_example_outside_a_declared_range_is_reported(course_copy: Path) -> None:
    path = course_copy / "exercises" / "boundaries" / "wrap.yaml"
    text = path.read_text().replace("  - {a: 4.0}\n", "  - {a: 9.0}\n")
    path.write_text(text)
    line = text.splitlines().index("  - {a: 9.0}") + 1
    problems = exercise_problems(course_copy, "boundaries/wrap")
    where = "exercises/boundaries/wrap.yaml"
    assert any(p.startswith(f"{where}:{line}: example value a: 9.0 is outside") for p in problems)


def test_the_fixture_exercises_declare_their_types() -> None:
    course = load_course(FIXTURE_COURSE)
    assert course.problems == []
    wrap = course.exercise("boundaries/wrap").options
    assert wrap.types == (ArgType("a", "angle", (-2 * PI, 2 * PI), line=wrap.types[0].line),)
    assert course.exercise("boundaries/add-noise").options.valid == "both_positive_definite"


def test_loading_the_module_imports_no_numpy() -> None:
    code = (
        "import sys\n"
        "from slamcourse.course.schema import Checker\n"
        "from slamcourse.grading import domains\n"
        "domains.parse_types({'a': 'angle', 'n': {'type': 'count', 'range': [1, 3]}}, "
        "['a', 'n'], Checker('x'))\n"
        "domains.boundary_classes([domains.ArgType('a', 'angle', (-3.0, 3.0))])\n"
        "domains.boundary_classes([domains.ArgType('R', 'rotation'), "
        "domains.ArgType('T', 'pose3', (-1.0, 1.0))])\n"
        "assert domains.outside(domains.ArgType('R', 'rotation'), "
        "[[0, -1, 0], [1, 0, 0], [0, 0, 1]]) is None\n"
        "assert 'numpy' not in sys.modules and 'hypothesis' not in sys.modules\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env={"PYTHONPATH": str(REPO / "src")},
        timeout=60,
    )
    assert done.returncode == 0, done.stderr


# ------------------------------------------------------------------------------ boundaries

POSES = (ArgType("a", "pose", (-20.0, 20.0)), ArgType("b", "pose", (-20.0, 20.0)))
POSE_BASES: list[dict[str, Any]] = [
    {"a": [0, 0, 0], "b": [3, -2, 0.5]},
    {"a": (1.5, -2.25, 0.3), "b": (4.1, 2.2, -1.2)},
    {"a": [-3.7, 8.1, -2.9], "b": [12.5, -0.4, 2.7]},
]
RICH = (
    ArgType("x", "real", (-50.0, 50.0)),
    ArgType("th", "angle", (-PI, PI)),
    ArgType("n", "count", (1, 200)),
    ArgType("p", "probability", (0.0, 1.0)),
    ArgType("v", "vector", (-10.0, 10.0), angles=(1,), ordered=False, ties=True, empty=True),
    ArgType("pose", "pose", (-20.0, 20.0)),
    ArgType("poses", "poses", (-20.0, 20.0), empty=True),
    ArgType("pts", "points", (-5.0, 5.0), ordered=False, ties=True, empty=True),
    ArgType("P", "covariance"),
    ArgType("W", "information", (0.01, 1e4)),
    ArgType("M", "matrix", (-3.0, 3.0)),
    ArgType("idx", "indices", ordered=False, ties=True, empty=True),
    ArgType("edges", "edges", ordered=False, ties=True, empty=True),
    ArgType("text", "g2o"),
    ArgType("rot", "rotation"),
    ArgType("T", "pose3", (-20.0, 20.0)),
    ArgType("e3", "edge3"),
    ArgType("doc", "text"),
    ArgType("c", "choice"),
    ArgType("d", "data"),
)
RICH_BASE: dict[str, Any] = {
    "x": 12.375,
    "th": 0.8,
    "n": 17,
    "p": 0.3,
    "v": [4.25, -0.7, 2.5],
    "pose": [1.25, -3.5, 2.2],
    "poses": [[0.0, 0.0, 0.0], [1.1, 0.2, 0.4], [2.05, 0.9, 1.1]],
    "pts": [[0.5, 1.25], [-2.0, 0.75], [1.5, -1.0]],
    "P": [[0.04, 0.01], [0.01, 0.03]],
    "W": [[10.0, 1.0], [1.0, 20.0]],
    "M": [[0.5, -1.25], [2.0, 0.75]],
    "idx": [2, 0, 1],
    "edges": [(0, 1, [1.0, 0.1, 0.2]), (1, 2, [0.9, 0.3, 0.4])],
    "text": G2O,
    "rot": ROTATION,
    "T": [[*ROTATION[0], 1.5], [*ROTATION[1], -2.25], [*ROTATION[2], 3.0], [0, 0, 0, 1]],
    "e3": EDGE3,
    "doc": "first line\nsecond line\n",
    "c": "a",
    "d": {"anything": 1},
}


def labels(derived: list[Derived]) -> set[str]:
    return {d.label for d in derived}


def first_of_each(derived: list[Derived]) -> dict[str, dict[str, Any]]:
    """The first input of each class (from the most preferred base)."""
    found: dict[str, dict[str, Any]] = {}
    for d in derived:
        found.setdefault(d.label, d.kwargs)
    return found


def test_every_class_is_derived_and_labelled_as_declared() -> None:
    derived = boundary_inputs(RICH, [RICH_BASE, dict(RICH_BASE, x=-3.0, th=-2.5)])
    assert labels(derived) == boundary_classes(RICH)
    expected = {
        "angle ±π (th)",
        "angle next to ±π (th)",
        "small angle (th)",
        "whole numbers as int (pose)",
        "int64 ndarray (poses)",
        "tuple of lists (pts)",
        "headings across ±π (poses)",
        "headings across ±π (th, pose)",
        "headings across ±π (v[1], pose)",
        "angle ±π (v[1])",
        "lowest value (n)",
        "highest value (n)",
        "identity (P)",
        "large scale (W)",
        "largest magnitudes (M)",
        "reversed order (idx)",
        "exact ties (edges)",
        "empty (pts)",
        "CRLF line ends (text)",
        "no final newline (doc)",
        "exponent notation (text)",
        "edge line first (text)",
        "probability ½ (p)",
        "identity (rot)",
        "small angle (rot)",
        "half turn (rot)",
        "just under π (rot)",
        "whole numbers as int (rot)",
        "int64 ndarray (rot)",
        "list of lists (rot)",
        "ndarray (rot)",
        "half turn (T)",
        "translation at range ends (T)",
        "exponent notation (e3)",
        "CRLF line ends (e3)",
    }
    assert expected <= boundary_classes(RICH)
    assert not any("(c)" in label or "(d)" in label for label in boundary_classes(RICH))
    assert "exponent notation (doc)" not in boundary_classes(RICH)
    assert "edge line first (e3)" not in boundary_classes(RICH)  # EDGE3 text has no vertices


def test_only_the_transformed_argument_changes() -> None:
    base = dict(RICH_BASE)
    for d in boundary_inputs(RICH, [base]):
        changed = [k for k in base if d.kwargs[k] is not base[k]]
        if d.label.startswith("headings across ±π (") and ", " in d.label:
            assert len(changed) == 2, d.label
        else:
            name = d.label.rsplit("(", 1)[1].rstrip(")").split("[")[0]
            assert changed in ([name], []), (d.label, changed)


def test_derived_inputs_are_deterministic_and_sendable() -> None:
    one = boundary_inputs(RICH, [RICH_BASE])
    two = boundary_inputs(RICH, [RICH_BASE])
    assert [(d.label, domains._key(d.kwargs)) for d in one] == [
        (d.label, domains._key(d.kwargs)) for d in two
    ]
    for d in one:
        for value in d.kwargs.values():
            encode_arg(value)  # raises for anything the sandbox cannot receive


def plain(value: Any) -> Any:
    """Nested values as lists of floats (a number's representation forgotten)."""
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, list | tuple):
        return [plain(v) for v in value]
    if isinstance(value, bool | str | dict):
        return value
    return float(value)


def g2o_lines(text: str) -> list[tuple[str, list[float]]]:
    """A g2o text's vertices and edges, in order, read the tolerant way."""
    rows = []
    for line in text.splitlines():
        fields = line.split()
        if fields:
            rows.append((fields[0], [float(f) for f in fields[1:]]))
    return rows


def test_representation_classes_keep_every_value() -> None:
    pure = representation_classes(RICH)
    assert {"tuple (pose)", "ndarray (poses)", "CRLF line ends (text)", "ndarray (T)"} <= pure
    assert "exponent notation (e3)" in pure and "half turn (rot)" not in pure
    assert "whole numbers as int (pose)" not in pure and "angle ±π (th)" not in pure
    for d in boundary_inputs(RICH, [RICH_BASE]):
        if d.label not in pure:
            continue
        name = d.label.rsplit("(", 1)[1].rstrip(")")
        got, base = d.kwargs[name], RICH_BASE[name]
        if name in ("text", "e3"):
            edges = [r for r in g2o_lines(got) if r[0].startswith("EDGE")]
            assert edges == [r for r in g2o_lines(base) if r[0].startswith("EDGE")]
            assert sorted(map(str, g2o_lines(got))) == sorted(map(str, g2o_lines(base)))
        elif name == "doc":
            assert got.split() == base.split()
        else:
            assert plain(got) == plain(base), d.label


def test_angles_reach_pi_exactly_and_the_floats_next_to_it() -> None:
    t = ArgType("a", "angle", (-PI, PI))
    values: dict[str, list[float]] = {d.label: [] for d in boundary_inputs([t], [{"a": 0.8}])}
    for d in boundary_inputs([t], [{"a": 0.8}, {"a": -1.9}]):
        values[d.label].append(d.kwargs["a"])
    assert sorted(set(values["angle ±π (a)"])) == [-PI, PI]
    assert math.nextafter(PI, 0) in values["angle next to ±π (a)"]
    assert math.nextafter(-PI, 0) in values["angle next to ±π (a)"]
    assert {1e-3, -7e-3} <= set(values["small angle (a)"])
    assert all(abs(v) < 0.01 and v != 0 for v in values["small angle (a)"])
    assert {type(v) for v in values["whole numbers as int (a)"]} == {int}
    half_open = ArgType("a", "angle", (-PI, PI), open="low")
    derived = boundary_inputs([half_open], [{"a": 0.8}])
    assert -PI not in [d.kwargs["a"] for d in derived]
    assert PI in [d.kwargs["a"] for d in derived]


@settings(max_examples=150, database=None, deadline=None)
@given(
    kind=st.sampled_from(["real", "angle", "probability", "count"]),
    ends=st.tuples(
        st.floats(-1e4, 1e4, allow_nan=False), st.floats(-1e4, 1e4, allow_nan=False)
    ).filter(lambda e: abs(e[0] - e[1]) > 1e-3),
    opening=st.sampled_from(domains._OPEN),
    bases=st.lists(st.floats(-1e5, 1e5, allow_nan=False), min_size=1, max_size=4),
)
def test_scalar_boundary_values_stay_in_the_declared_range(
    kind: str, ends: tuple[float, float], opening: str, bases: list[float]
) -> None:
    low, high = sorted(ends)
    if kind == "probability":
        low, high = sorted((abs(low) % 1, abs(high) % 1))
        if high - low < 1e-3:
            return
    if kind == "count":
        low, high = math.floor(low), math.ceil(high)
        opening = "none"
    t = ArgType("x", kind, (low, high), open=opening)
    derived = boundary_inputs([t], [{"x": b} for b in bases])
    assert labels(derived) <= boundary_classes([t])
    for d in derived:
        x = d.kwargs["x"]
        assert isinstance(x, int | float) and not isinstance(x, bool)
        assert t.contains(x), (d.label, x, t)
        if kind == "count" or d.label.startswith("whole numbers"):
            assert type(x) is int


@settings(max_examples=100, database=None, deadline=None)
@given(
    poses=st.lists(
        st.tuples(
            st.floats(-5, 5, allow_nan=False),
            st.floats(-5, 5, allow_nan=False),
            st.floats(-PI, PI, allow_nan=False),
        ),
        min_size=2,
        max_size=6,
    )
)
def test_turning_a_set_of_poses_keeps_the_poses_relative_to_each_other(
    poses: list[tuple[float, float, float]],
) -> None:
    t = ArgType("poses", "poses")
    base = {"poses": [list(p) for p in poses]}
    for d in boundary_inputs([t], [base]):
        if not (d.label.startswith("angle") or d.label.startswith("headings")):
            continue
        moved = d.kwargs["poses"]
        assert all(-PI <= p[2] <= PI for p in moved)
        for i in range(len(poses)):
            for j in range(len(poses)):
                want, got = _between(poses[i], poses[j]), _between(moved[i], moved[j])
                assert math.isclose(want[0], got[0], abs_tol=1e-9)
                assert math.isclose(want[1], got[1], abs_tol=1e-9)
                assert abs(math.remainder(want[2] - got[2], 2 * PI)) < 1e-9
        if d.label.startswith("angle ±π ("):
            assert moved[-1][2] in (PI, -PI)


def _between(a: Any, b: Any) -> tuple[float, float, float]:
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]


def test_headings_either_side_of_pi_keep_the_other_entries() -> None:
    derived = [d for d in boundary_inputs(POSES, POSE_BASES) if d.label.startswith("headings")]
    assert {d.label for d in derived} == {"headings across ±π (a, b)"}
    for d in derived:
        a, b = d.kwargs["a"], d.kwargs["b"]
        assert abs(a[2]) > 3 and abs(b[2]) > 3 and a[2] * b[2] < 0
        assert abs(math.remainder(b[2] - a[2], 2 * PI)) <= 0.1 + 1e-12
        assert all(v != 0 for v in [*a[:2], *b[:2]])  # a non-trivial base was chosen
    poses = boundary_inputs([ArgType("poses", "poses")], [{"poses": RICH_BASE["poses"]}])
    [across] = [d.kwargs["poses"] for d in poses if d.label.startswith("headings")][:1]
    headings = [p[2] for p in across]
    assert any(abs(h1 - h2) > PI for h1, h2 in itertools.pairwise(headings))


def test_whole_numbers_arrive_as_ints_and_int64_arrays() -> None:
    derived = first_of_each(boundary_inputs(POSES, POSE_BASES[1:2]))
    whole = derived["whole numbers as int (a)"]["a"]
    assert isinstance(whole, tuple) and [type(v) for v in whole] == [int, int, int]
    assert whole == (2, -2, 0)
    array = derived["int64 ndarray (b)"]["b"]
    assert isinstance(array, np.ndarray) and array.dtype == np.int64
    assert isinstance(derived["ndarray (a)"]["a"], np.ndarray)
    assert isinstance(derived["list (a)"]["a"], list)


def test_sequences_come_as_lists_tuples_and_arrays() -> None:
    derived = first_of_each(boundary_inputs(RICH, [RICH_BASE]))
    assert isinstance(derived["tuple (v)"]["v"], tuple)
    pts = derived["list of tuples (pts)"]["pts"]
    assert isinstance(pts, list) and all(isinstance(p, tuple) for p in pts)
    pts = derived["tuple of lists (pts)"]["pts"]
    assert isinstance(pts, tuple) and all(isinstance(p, list) for p in pts)
    assert derived["ndarray (idx)"]["idx"].dtype == np.int64
    assert derived["reversed order (idx)"]["idx"] == [1, 0, 2]
    assert derived["exact ties (pts)"]["pts"] == RICH_BASE["pts"] * 2
    assert derived["empty (edges)"]["edges"] == []
    edges = derived["tuple of lists (edges)"]["edges"]
    assert isinstance(edges, tuple) and edges[0] == [0, 1, [1.0, 0.1, 0.2]]


def test_covariances_stay_symmetric_positive_definite() -> None:
    derived = boundary_inputs(RICH, [RICH_BASE, dict(RICH_BASE, P=[[2.5, 0.4], [0.4, 0.9]])])
    for d in derived:
        for name in ("P", "W"):
            if d.label.endswith(f"({name})"):
                m = np.asarray(d.kwargs[name], dtype=float)
                assert np.array_equal(m, m.T) and np.linalg.eigvalsh(m).min() > 0, d.label
    by = first_of_each(derived)
    assert by["identity (P)"]["P"] == [[1, 0], [0, 1]]
    assert all(type(x) is int for row in by["whole numbers as int (P)"]["P"] for x in row)
    assert by["int64 ndarray (W)"]["W"].dtype == np.int64
    assert np.asarray(by["large scale (W)"]["W"]).max() == 1e4  # the declared range's top
    assert np.asarray(by["small scale (W)"]["W"]).diagonal().min() == 0.01
    assert np.isclose(np.asarray(by["large scale (P)"]["P"])[0][0], 40.0)


def test_g2o_texts_in_other_spellings() -> None:
    derived = {k: v["text"] for k, v in first_of_each(boundary_inputs(RICH, [RICH_BASE])).items()}
    crlf = derived["CRLF line ends (text)"]
    assert crlf.count("\r\n") == G2O.count("\n") and "\n" not in crlf.replace("\r\n", "")
    assert derived["no final newline (text)"] == G2O.rstrip("\n")
    exp = derived["exponent notation (text)"]
    assert "7.74115e-01" in exp and "EDGE_SE2 0 1 " in exp and "VERTEX_SE2 1 " in exp
    assert g2o_lines(exp) == g2o_lines(G2O)
    first = derived["edge line first (text)"]
    assert first.startswith("EDGE_SE2 0 1 ") and first.endswith("\n")
    padded = derived["blank lines and trailing spaces (text)"]
    assert padded.startswith("\n") and "  \n" in padded and "\n\n" in padded
    no_newline = G2O.rstrip("\n").replace("EDGE_SE2 1 0", "VERTEX_SE2 2 0")
    moved = boundary_inputs([ArgType("t", "g2o")], [{"t": no_newline}])
    [text] = [d.kwargs["t"] for d in moved if d.label == "edge line first (t)"]
    assert text.startswith("EDGE_SE2") and not text.endswith("\n")


def test_counts_reach_both_ends_as_ints_from_the_nearest_bases() -> None:
    t = ArgType("n", "count", (1, 30000))
    bases = [{"n": 5, "k": 0}, {"n": 29000, "k": 1}, {"n": 2, "k": 2}, {"n": 9, "k": 3}]
    by: dict[str, list[dict[str, Any]]] = {}
    for d in boundary_inputs([t], bases):
        by.setdefault(d.label, []).append(d.kwargs)
    assert [kw["k"] for kw in by["lowest value (n)"]] == [2, 0][: domains.SPREAD]
    assert [kw["k"] for kw in by["highest value (n)"]] == [1, 3][: domains.SPREAD]
    assert all(type(kw["n"]) is int for kws in by.values() for kw in kws)


def test_a_class_every_base_already_has_is_shown_by_the_last_bases() -> None:
    t = ArgType("v", "vector")
    bases = [{"v": [1.5, 2.5], "k": k} for k in range(4)]
    derived = [d for d in boundary_inputs([t], bases) if d.label == "list (v)"]
    assert [d.kwargs["k"] for d in derived] == [3, 2][: domains.SPREAD]
    arrays = [{"v": np.array([1.5, 2.5 + k])} for k in range(3)]
    derived = [d for d in boundary_inputs([t], arrays) if d.label == "ndarray (v)"]
    assert [d.kwargs["v"][1] for d in derived] == [4.5, 3.5][: domains.SPREAD]


def test_bases_of_another_shape_are_skipped_and_the_limit_holds() -> None:
    t = ArgType("a", "pose")
    assert boundary_inputs([t], [{"a": "not a pose"}, {"b": 1}]) == []
    derived = boundary_inputs([t], [{"a": [1.0, 2.0]}, {"a": [1.0, 2.0, 0.5]}])
    assert derived and all(len(plain(d.kwargs["a"])) == 3 for d in derived)
    assert len(boundary_inputs(RICH, [RICH_BASE], limit=7)) == 7


def test_ranges_are_respected_by_sequences_too() -> None:
    derived = boundary_inputs(RICH, [RICH_BASE, dict(RICH_BASE, pts=[[4.5, -4.0], [3.0, 1.0]])])
    for d in derived:
        for name, low, high in (("pose", -20, 20), ("pts", -5, 5), ("M", -3, 3), ("v", -10, 10)):
            if d.label.endswith(f"({name})"):
                values = np.asarray(plain(d.kwargs[name]), dtype=float).ravel()
                assert values.size == 0 or (low <= values.min() and values.max() <= high)
    by = first_of_each(derived)
    assert np.asarray(by["largest magnitudes (M)"]["M"]).max() == 3.0
    corners = [d.kwargs["pts"] for d in derived if d.label == "positions at range ends (pts)"]
    assert max(p[0] for p in corners[0]) == 5.0 and max(p[1] for p in corners[0]) == 5.0
    assert min(p[0] for p in corners[1]) == -5.0 and min(p[1] for p in corners[1]) == -5.0


def test_assumptions_filter_derived_inputs() -> None:
    args = [Argument("dx", "float", (-20, 20), 1), Argument("dy", "float", (-20, 20), 2)]
    holds = domains.assumptions(args, ["hypot(dx, dy) > 0.001"])
    assert holds is not None and holds(dx=1.0, dy=0.0) and not holds(dx=0, dy=0.0)
    assert domains.assumptions(args, []) is None


def test_deriving_is_fast() -> None:
    spec = load_course(FIXTURE_COURSE).exercise("boundaries/pose-distance")
    bases = [
        *POSE_BASES,
        *[{"a": [0.1 * k, 2.0, 0.3], "b": [1.0, -0.2 * k, 1.0]} for k in range(12)],
    ]
    boundary_inputs(spec.options.types, bases)  # numpy imported
    start = time.perf_counter()
    for _ in range(10):
        boundary_inputs(spec.options.types, bases)
    assert (time.perf_counter() - start) / 10 < 0.05


# ------------------------------------------------------------------------------ rotations


def test_rotation_pose3_and_edge3_parse() -> None:
    text = "types:\n  R: rotation\n  T: {type: pose3, range: [-50, 50]}\n  t: edge3\n"
    types, check = parse(text, ["R", "T", "t"])
    assert check.problems == []
    assert [(t.type, t.bounds) for t in types] == [
        ("rotation", None),
        ("pose3", (-50.0, 50.0)),
        ("edge3", None),
    ]
    _types, check = parse("types:\n  R: {type: rotation, size: 3}\n", ["R"])
    assert any("it takes no parameters" in m for m in messages(check)), messages(check)


def _angle_axis(m: Any) -> tuple[float, np.ndarray]:
    """Angle and unit axis by scipy (an independent route), the axis's sign free."""
    from scipy.spatial.transform import Rotation  # type: ignore[import-untyped]

    w = Rotation.from_matrix(np.asarray(m, dtype=float)).as_rotvec()
    angle = float(np.linalg.norm(w))
    return angle, (w / angle if angle > 0 else w)


def _rotation_of(axis: tuple[float, float, float], angle: float) -> list[list[float]]:
    from scipy.spatial.transform import Rotation

    n = np.array(axis) / np.linalg.norm(axis)
    out: list[list[float]] = Rotation.from_rotvec(angle * n).as_matrix().tolist()
    return out


ROTATION_TYPE = ArgType("R", "rotation")


@settings(max_examples=60, database=None, deadline=None)
@given(
    axis=st.tuples(
        st.floats(-1, 1, allow_nan=False),
        st.floats(-1, 1, allow_nan=False),
        st.floats(-1, 1, allow_nan=False),
    ).filter(lambda v: math.hypot(*v) > 0.1),
    angle=st.one_of(st.floats(1e-6, PI), st.floats(PI - 1e-3, PI)),
    array=st.booleans(),
)
def test_every_rotation_class_is_a_rotation_with_its_promised_angle(
    axis: tuple[float, float, float], angle: float, array: bool
) -> None:
    base = _rotation_of(axis, angle)
    given_r: Any = np.array(base) if array else base
    _, base_axis = _angle_axis(base)
    derived = boundary_inputs([ROTATION_TYPE], [{"R": given_r}])
    assert labels(derived) == boundary_classes([ROTATION_TYPE])
    for d in derived:
        r = d.kwargs["R"]
        m = np.asarray(r, dtype=float)
        assert domains.rotation_problem(r) is None, d.label
        assert np.abs(m.T @ m - np.eye(3)).max() <= 1e-12 and np.linalg.det(m) > 0
        _, got_axis = _angle_axis(m)
        own_axis = abs(float(got_axis @ base_axis)) > 1 - 1e-6
        sin = float(np.linalg.norm([m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]])) / 2
        if d.label == "identity (R)":
            assert np.array_equal(m, np.eye(3)) and type(r) is type(given_r)
        elif d.label == "small angle (R)":
            assert own_axis
            assert any(math.isclose(sin, a, rel_tol=1e-6) for a in domains.SMALL_TURNS)
        elif d.label == "half turn (R)":
            assert own_axis and np.array_equal(m, m.T) and abs(np.trace(m) + 1) < 1e-12
        elif d.label == "just under π (R)":
            # sin θ = sin(π − θ): the antisymmetric part measures how far below π it turns
            assert own_axis and any(math.isclose(sin, u, rel_tol=1e-3) for u in domains.UNDER_PI)
        elif d.label in ("whole numbers as int (R)", "int64 ndarray (R)"):
            if d.label.startswith("int64"):
                assert r.dtype == np.int64
            else:
                assert all(type(x) is int for row in r for x in row)
            assert sorted(np.abs(m).ravel().tolist()) == [0] * 6 + [1] * 3
            assert not np.array_equal(m, np.eye(3))
            scores = [float(np.sum(np.array(p) * base)) for p in domains._signed_permutations()]
            assert float(np.sum(m * base)) >= max(scores[1:]) - 1e-12  # the nearest (or a tie)
        else:  # the container forms: the same numbers
            assert np.array_equal(m, np.asarray(base)), d.label
            assert isinstance(r, np.ndarray) == (d.label == "ndarray (R)")


def test_the_whole_number_rotations_are_the_24_turns_of_a_cube() -> None:
    turns = domains._signed_permutations()
    assert len(turns) == 24 and turns[0] == [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    assert len({str(t) for t in turns}) == 24
    assert all(round(np.linalg.det(np.array(t))) == 1 for t in turns)


def test_a_base_that_is_not_a_rotation_gets_no_rotation_classes() -> None:
    reflection = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]
    sheared = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    for bad in (reflection, sheared, [[1.0, 0.0], [0.0, 1.0]], "R"):
        assert boundary_inputs([ROTATION_TYPE], [{"R": bad}]) == []
    identity = boundary_inputs([ROTATION_TYPE], [{"R": np.eye(3)}])
    assert "half turn (R)" not in labels(identity)  # the identity has no axis to turn about
    assert "whole numbers as int (R)" in labels(identity)


def test_the_domain_check_reports_examples_that_are_not_rotations() -> None:
    t = ROTATION_TYPE
    assert domains.outside(t, ROTATION) is None
    assert domains.outside(t, np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]])) is None
    flipped = domains.outside(t, [[1, 0, 0], [0, 1, 0], [0, 0, -1]])
    assert flipped == "the matrix is a reflection (determinant −1), not a rotation (type rotation)"
    rounded = [[round(x, 6) for x in row] for row in ROTATION]  # orthonormal to only ~1e-6
    assert "RᵀR differs from I by" in str(domains.outside(t, rounded))
    assert "not a 3 × 3 matrix" in str(domains.outside(t, [[1, 0], [0, 1]]))
    assert "not finite" in str(domains.outside(t, [[math.nan, 0, 0], [0, 1, 0], [0, 0, 1]]))
    pose = ArgType("T", "pose3", (-2.0, 2.0))
    good = [[*ROTATION[0], 1.5], [*ROTATION[1], -2.0], [*ROTATION[2], 0.0], [0, 0, 0, 1]]
    assert domains.outside(pose, good) is None
    assert "last row" in str(domains.outside(pose, [*good[:3], [0, 0, 0, 2]]))
    assert "outside the declared range [-2, 2]" in str(
        domains.outside(pose, [*good[:2], [*ROTATION[2], 2.5], good[3]])
    )
    assert "rotation block" in str(
        domains.outside(pose, [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 0], [0, 0, 0, 1]])
    )


def test_pose3_classes_turn_the_rotation_block_and_move_the_translation() -> None:
    t = ArgType("T", "pose3", (-20.0, 20.0))
    base = RICH_BASE["T"]
    derived = boundary_inputs([t], [{"T": base}, {"T": np.array(base, dtype=float)}])
    assert labels(derived) == boundary_classes([t])
    ends = []
    for d in derived:
        m = np.asarray(d.kwargs["T"], dtype=float)
        assert m.shape == (4, 4) and domains.pose3_problem(d.kwargs["T"], t) is None, d.label
        assert m[3].tolist() == [0, 0, 0, 1]
        if d.label == "translation at range ends (T)":
            ends.append(m[:3, 3].tolist())
            assert np.array_equal(m[:3, :3], np.asarray(ROTATION))
        elif d.label.startswith(("whole numbers", "int64")):
            assert m[:3, 3].tolist() == [2, -2, 3]  # 1.5, -2.25, 3.0 rounded
            assert np.asarray(d.kwargs["T"]).dtype.kind == "i"
        else:
            assert m[:3, 3].tolist() == [1.5, -2.25, 3.0], d.label  # the translation kept
    assert [20.0] * 3 in ends and [-20.0] * 3 in ends
    by = first_of_each(derived)
    assert np.array_equal(np.asarray(by["identity (T)"]["T"])[:3, :3], np.eye(3))
    half = np.asarray(by["half turn (T)"]["T"])[:3, :3]
    assert np.array_equal(half, half.T) and not np.array_equal(half, np.eye(3))
    assert "translation at range ends (T)" not in boundary_classes([ArgType("T", "pose3")])


def test_edge3_text_in_exponent_notation_keeps_its_tags_ids_and_values() -> None:
    t = ArgType("t", "edge3")
    assert boundary_classes([t]) == {
        "CRLF line ends (t)",
        "no final newline (t)",
        "blank lines and trailing spaces (t)",
        "exponent notation (t)",
    }
    derived = {d.label: d.kwargs["t"] for d in boundary_inputs([t], [{"t": EDGE3}])}
    exp = derived["exponent notation (t)"]
    assert exp.startswith("EDGE3 0 1 1.08756e+00 2.58927e-01 ") and "EDGE3 1 2 6.06173e-01" in exp
    assert g2o_lines(exp) == g2o_lines(EDGE3)


def test_large_bases_come_last_and_inadmissible_inputs_do_not_count() -> None:
    """A class is about values and types, not size: a base far larger than the others (a real
    data set among small synthetic ones) is used only where the small ones give no input in
    the domain; an input ``admissible`` rejects does not count towards a class's inputs."""
    t = ArgType("v", "vector")
    small = [{"v": [1.5, 2.5 + k], "k": k} for k in range(4)]
    large = {"v": [0.5 + i for i in range(200)], "k": 99}
    derived = [d for d in boundary_inputs([t], [large, *small]) if d.label == "tuple (v)"]
    assert len(derived) == domains.SPREAD and 99 not in [d.kwargs["k"] for d in derived]
    without_large = [d for d in boundary_inputs([t], small) if d.label == "tuple (v)"]
    assert [d.kwargs for d in derived] == [d.kwargs for d in without_large]

    def only_large(kwargs: dict[str, Any]) -> bool:
        return len(kwargs["v"]) > 100

    derived = [
        d
        for d in boundary_inputs([t], [large, *small], admissible=only_large)
        if d.label == "tuple (v)"
    ]
    assert [d.kwargs["k"] for d in derived] == [99]  # the small ones were tried and refused
    seen: list[int] = []

    def the_third(kwargs: dict[str, Any]) -> bool:
        seen.append(kwargs["k"])
        return kwargs["k"] >= 2

    derived = [
        d for d in boundary_inputs([t], small, admissible=the_third) if d.label == "tuple (v)"
    ]
    assert [d.kwargs["k"] for d in derived] == [2, 3][: domains.SPREAD]  # in the domain
    assert seen[0] == 1  # (tried first, refused)


def test_a_base_whose_output_is_large_comes_last_too() -> None:
    """``size`` weighs a base by what it costs (a test set adds the reference's output): a
    count that makes the function compute and return n samples is as large as n values."""
    t = ArgType("v", "vector")
    bases = [{"v": [1.5, 2.5], "n": n} for n in (2000, 1500, 20, 30, 40)]
    plain = [d.kwargs["n"] for d in boundary_inputs([t], bases) if d.label == "tuple (v)"]
    assert plain == [2000, 1500][: domains.SPREAD]  # (equal inputs: the order given)

    def with_output(base: dict[str, Any]) -> int:
        return domains.input_size(base) + 3 * base["n"]

    sized = [
        d.kwargs["n"]
        for d in boundary_inputs([t], bases, size=with_output)
        if d.label == "tuple (v)"
    ]
    assert sized == [20, 30][: domains.SPREAD]


def test_an_empty_sequence_in_another_form_is_a_last_resort() -> None:
    """``[]`` as a tuple or an array shows nothing a function could get wrong (an in-place
    change of an empty array changes nothing): such a class is derived from a base whose
    argument holds values, where there is one."""
    t = ArgType("s", "vector")
    bases = [{"s": [], "k": 1.5}, {"s": [0.3, 4.5], "k": 2.5}]
    by = first_of_each(boundary_inputs([t], bases))
    assert list(by["ndarray (s)"]["s"]) == [0.3, 4.5] and by["tuple (s)"]["s"] == (0.3, 4.5)
    alone = first_of_each(boundary_inputs([t], bases[:1]))
    assert len(alone["ndarray (s)"]["s"]) == 0  # nothing better: the empty one still shows it
