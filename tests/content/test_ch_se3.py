"""Chapter ``se3``: its pinned figures, the answers of its exercises against independent
computations, its drawings, how many mutants and variants its code exercises ship, and the
argument types' boundary classes that catch some of those mutants without the examples. (That
every mutant is rejected and every variant accepted in the real sandbox is checked once, by
``test_bundled_course.py::test_exercise_is_sound``.)"""

from __future__ import annotations

import dataclasses
import functools
import importlib.util
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from scipy.spatial.transform import Rotation  # type: ignore[import-untyped]

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.grading import testset
from slamcourse.plots import ch_se3
from slamcourse.slam import se3
from tests.callees import in_process, load

ROOT = Path(__file__).resolve().parents[2]
CHAPTER = ROOT / "chapters" / "22-se3.md"
COURSE = load_course(bundled_course_root())


def _load() -> ModuleType:
    path = ROOT / "exercises" / "se3" / "reference.py"
    spec = importlib.util.spec_from_file_location("_ref_se3", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ref = _load()


# --- answers against independent computations -------------------------------------------------


def test_numeric_answers() -> None:
    assert ref.rotation_angle(theta=2.1, tr=1 + 2 * math.cos(2.1)) == pytest.approx(2.1)
    w, p = [0.6, -0.3, 0.9], [1, 2, 0.5]
    expected = Rotation.from_rotvec(w).apply(p)
    assert ref.rotated_point(*w, *p) == pytest.approx(expected)
    assert np.linalg.norm(ref.rotated_point(*w, *p)) == pytest.approx(np.linalg.norm(p))
    # the world turned by 0.1 rad about z, a robot at (2, 0, 1) facing +y: it swings forward
    assert ref.right_from_left(yaw=math.pi / 2, tx=2, ty=0, tz=1) == pytest.approx(
        [0.2, 0, 0, 0, 0, 0.1], abs=1e-12
    )
    assert ref.yaw_sigma() == pytest.approx(0.04)
    assert ref.mistake_yaw_sigma_information() == pytest.approx(0.2)
    assert ref.sphere_dof() == 6 * 4949 - 6 * 2499 == 14700


def test_sphere2500_figures() -> None:
    """Every figure the prose quotes about the whole graph (one optimisation, cached)."""
    graph = ref.sphere()
    x, history = se3.optimise_text(ref.sphere_text(), 10)
    assert history[0] == pytest.approx(26.4e6, rel=0.01)  # "about 26 million"
    assert abs(history[6] - history[10]) < 1e-3  # "in six steps"
    assert history[5] - history[10] > 1e-3
    assert history[10] == pytest.approx(ref.sphere_chi2())
    assert history[10] / 14700 == pytest.approx(1, abs=0.01)  # "within one percent"
    assert 19 < history[10] / ref.mistake_sphere_chi2_information() < 21  # "twenty times"
    truth = se3.positions_from_first(ref.truth().poses)

    # ATE computed independently: scipy's Rotation.align_vectors on centred points
    def ate(points: np.ndarray) -> float:
        pc, tc = points - points.mean(0), truth - truth.mean(0)
        rot, _ = Rotation.align_vectors(tc, pc)
        return float(np.sqrt(np.mean(np.sum((rot.apply(pc) - tc) ** 2, axis=1))))

    assert ate(se3.positions_from_first(x)) == pytest.approx(0.18, abs=0.005)  # "0.18 m"
    assert ate(se3.positions_from_first(graph.poses)) == pytest.approx(28, abs=0.5)  # "28 m"
    assert ref.sphere_ate() == pytest.approx(ate(se3.positions_from_first(x)), rel=1e-6)
    assert 6 * 2499 == 14994 and pytest.approx(1.8, abs=0.01) == 14994**2 * 8 / 1e9


def test_float_facts_of_the_prose() -> None:
    assert math.cos(1e-8) == 1.0 and math.cos(2e-8) < 1.0  # "rounds to 1 below about 1e-8"
    _, errors = ch_se3.log_errors()
    assert max(errors["robust"]) < 1e-14  # "near 1e-15 everywhere"
    assert max(errors["acos"]) > 1  # "loses everything near π"
    assert 1e-8 < max(errors["atan2"]) < 1e-6  # "grows like 1e-16/(π − θ)"


def test_prose_quotes_the_pinned_numbers() -> None:
    prose = CHAPTER.read_text(encoding="utf-8")
    for quoted in ("2450 loop", "14700", "0.18 m", "0.012 rad", "0.100 m", "0.040 rad", "14994"):
        assert quoted in prose, quoted
    assert re.findall(r"```\{figure\} (se3/[a-z-]+)", prose) == ["se3/log-accuracy", "se3/sphere"]


def test_windows_are_in_the_domain() -> None:
    text = ref.sphere_window(300, 120)
    assert ref.graph_valid(text, 10)
    assert not ref.graph_valid(text, 31)
    assert not ref.graph_valid(ref.sphere_text(), 3)  # the whole graph only with 10 steps
    assert ref.rotation_valid([[1, 0, 0], [0, -1, 0], [0, 0, -1]])
    assert not ref.rotation_valid([[1, 0, 0], [0, 1, 0], [0, 0, -1]])  # a reflection
    assert ref.rotation_valid([[-1, 0, 0], [0, -1, 0], [0, 0, 1]])  # a half turn about z
    assert not ref.rotation_valid([[0, 1, 0], [1, 0, 0], [0, 0, -1]])  # about (1, 1, 0): a tie


# --- drawings ---------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(ch_se3.FIGURES))
def test_figures_are_accessible_svg(name: str) -> None:
    svg = ch_se3.FIGURES[name]()
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    assert root.find(f"{ns}title") is not None and root.find(f"{ns}desc") is not None


@pytest.mark.parametrize("name", sorted(ch_se3.PICTURES))
def test_pictures_draw_the_givens(name: str) -> None:
    svg = ch_se3.PICTURES[name].draw({}, False)
    ET.fromstring(svg)
    assert "<title" in svg and "<desc" in svg
    assert COURSE.exercise(name).kind == "code"


# --- enough mutants and variants --------------------------------------------------------------


def test_enough_mutants_and_variants() -> None:
    for slug in ("so3-log", "optimise-3d"):
        folder = ROOT / "exercises" / "se3"
        mutants = sorted((folder / "mutants" / slug).glob("*.py"))
        variants = sorted((folder / "variants" / slug).glob("*.py"))
        assert len(mutants) >= 8 and len(variants) >= 3
        assert all(p.read_text(encoding="utf-8").startswith("# mistake: ") for p in mutants)
        assert all(p.read_text(encoding="utf-8").startswith("# method: ") for p in variants)


# --- the argument types' classes catch their mistakes (examples removed) -------------------------

# (exercise, mutant, boundary class, only that class catches it among the examples-free inputs)
TYPE_CLASSES = [
    ("se3/so3-log", "12-no-zero-branch.py", "identity (R)", True),
    ("se3/so3-log", "11-output-like-input.py", "whole numbers as int (R)", True),
    ("se3/so3-log", "11-output-like-input.py", "int64 ndarray (R)", True),
    ("se3/so3-log", "13-antisymmetric-in-place.py", "ndarray (R)", True),
    ("se3/so3-log", "01-acos.py", "just under π (R)", False),
    ("se3/so3-log", "10-tiny-is-identity.py", "small angle (R)", False),
    ("se3/so3-log", "06-first-component-positive.py", "half turn (R)", False),
    ("se3/optimise-3d", "12-regex-without-exponent.py", "exponent notation (text)", False),
]


@functools.cache
def _without_examples(exercise: str) -> testset.TestSet:
    spec = COURSE.exercise(exercise)
    bare = dataclasses.replace(spec, options=dataclasses.replace(spec.options, examples=()))
    return testset.build(bare)


@pytest.mark.parametrize(("exercise", "mutant", "label", "only"), TYPE_CLASSES)
def test_a_type_class_rejects_its_mutant_without_the_examples(
    exercise: str, mutant: str, label: str, only: bool
) -> None:
    """The generic mechanism, not an example: the exercise's test set without its examples
    reaches the class, and the mutant fails on the class's inputs (and, where ``only``, passes
    every other input: nothing else would have caught it)."""
    opts = COURSE.exercise(exercise).options
    tests = _without_examples(exercise)
    assert label in tests.boundary_classes
    path = ROOT / "exercises" / "se3" / "mutants" / exercise.split("/")[1] / mutant
    call_many = in_process(load(path, opts.function))
    failed = set()
    for case in tests.cases:
        if not only and case.origin != f"boundary: {label}":
            continue
        outcome, _ = testset.run_cases(
            tests,
            call_many,
            signature=opts.signature,
            returns=opts.returns,
            tolerance=opts.tolerance,
            mutable=opts.mutates,
            cases=[case],
        )
        if not outcome.passed:
            failed.add(case.origin)
    assert f"boundary: {label}" in failed, f"{mutant} passes {label!r}"
    if only:  # no drawn input catches it: without the class, the mistake would pass
        assert all(o.startswith("boundary: ") for o in failed), failed
