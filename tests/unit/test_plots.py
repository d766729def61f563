"""Pictures drawn from parameters: well-formed SVG, a text alternative, the parameters' numbers."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from slamcourse.plots.drift import drift_trajectories, heading_path
from slamcourse.plots.geometry import observation_geometry, wrap
from slamcourse.plots.occupancy import beam_cells, occupancy_grid, occupancy_ray, update_grid
from slamcourse.plots.registry import BY_ID, has_plot, plot_for
from slamcourse.plots.sparsity import eliminate, information_sparsity
from slamcourse.plots.svg import num

NS = "{http://www.w3.org/2000/svg}"


def parsed(svg: str) -> tuple[ET.Element, str, str]:
    root = ET.fromstring(svg)
    assert root.tag == f"{NS}svg"
    assert root.get("role") == "img"
    title = root.find(f"{NS}title")
    desc = root.find(f"{NS}desc")
    assert title is not None and title.text and desc is not None and desc.text
    assert root.get("aria-labelledby") == f"{title.get('id')} {desc.get('id')}"
    return root, title.text, desc.text


def test_systematic_drift_states_b_times_k() -> None:
    _, title, desc = parsed(drift_trajectories(957, bias=0.041))
    assert "drift" in title.lower()
    assert f"{num(0.041 * 957)} m ahead" in desc


def test_random_walk_states_sigma_sqrt_k() -> None:
    _, _, desc = parsed(drift_trajectories(400, sigma=0.05, seed=3))
    assert f"1σ error of {num(0.05 * 20)} m" in desc


def test_heading_drift_path_and_description() -> None:
    path = heading_path(0.5, 0.01, 100)
    lateral = sum(0.5 * math.sin(0.01 * k) for k in range(1, 101))
    assert path[-1][1] == pytest.approx(lateral)
    _, _, desc = parsed(drift_trajectories(100, step_length=0.5, heading_rate=0.01))
    assert f"{num(lateral)} m to the side" in desc


def test_observation_geometry_range_and_wrapped_bearing() -> None:
    # behind and to the left: the bearing wraps past π
    _, _, desc = parsed(observation_geometry(0, 0, 3.0, -4, -1))
    phi = wrap(math.atan2(-1, -4) - 3.0)
    assert -math.pi < phi <= math.pi
    assert f"r = {num(math.hypot(4, 1))} m" in desc
    assert f"φ = {num(phi)} rad" in desc


def test_open_exercises_get_no_answer_from_their_picture() -> None:
    params = {"xr": 2.0, "yr": 3.0, "thr": 0.5, "xj": 5.0, "yj": 7.0}
    tags = ("observation-model",)
    shown = plot_for("observation/predicted-range", tags, params, solved=True)
    hidden = plot_for("observation/predicted-range", tags, params, solved=False)
    assert shown is not None and hidden is not None
    assert "r = 5 m" in shown and "r = 5 m" not in hidden and "r = ?" in hidden
    assert "φ = ?" in hidden and "r = 5 m" not in parsed(hidden)[2]
    # a picture that is the answer (a count of fill-in cells) waits for the solve
    assert plot_for("factor-graphs/star-fill-in", (), {"leaves": 4}, solved=False) is None
    assert plot_for("factor-graphs/star-fill-in", (), {"leaves": 4}, solved=True) is not None
    assert plot_for("drift/systematic-drift", (), {"steps": 10, "bias": 0.1}, solved=False) is None


def test_elimination_fill_in() -> None:
    chain = [(i, i + 1) for i in range(4)]
    assert eliminate(5, chain, range(5))[1] == set()  # a chain eliminated in order: no fill-in
    _, fill = eliminate(5, chain, [2, 0, 1, 3, 4])
    assert fill == {(1, 3), (3, 1)}
    star = [(0, k) for k in range(1, 5)]
    _, fill = eliminate(5, star, [0])
    assert len(fill) == 4 * 3  # every ordered pair of leaves
    _, _, desc = parsed(information_sparsity(5, star, order=[0]))
    assert "12 are fill-in" in desc and "13 non-zero entries out of 25" in desc


def test_sparsity_refuses_huge_matrices() -> None:
    with pytest.raises(ValueError, match="at most"):
        information_sparsity(1000, [])


def test_beam_cells_and_grid_update() -> None:
    assert beam_cells((0, 0), (3, 0)) == [(0, 0), (1, 0), (2, 0), (3, 0)]
    assert beam_cells((0, 0), (2, 2)) == [(0, 0), (1, 1), (2, 2)]
    grid = update_grid(4, 1, (0, 0), [(3, 0), (3, 0)], 0.85, -0.4)
    assert grid[0] == pytest.approx([0.0, -0.8, -0.8, 1.7])
    _, _, desc = parsed(occupancy_grid(4, 1, (0, 0), [(3, 0)], 0.85, -0.4))
    assert "1 cells have positive log-odds" in desc


def test_ray_update_before_and_after() -> None:
    _, _, desc = parsed(occupancy_ray([1.0, -0.5, 0.2, 2.0, 0.0], 3, 0.85, -0.4))
    assert "After: 0.6, −0.9, −0.2, 2.85, 0" in desc


def test_text_is_escaped() -> None:
    svg = occupancy_ray([0.0], 0, 0.85, -0.4)
    assert "<script" not in svg
    ET.fromstring(svg)


def test_every_registered_picture_draws_from_the_bundled_course(tmp_path: Path) -> None:
    """The registry's parameter names match the course: each entry draws variants 0 and 1."""
    from slamcourse.course.loader import load_course
    from slamcourse.course.variants import variant
    from tests.conftest import REPO

    course = load_course(REPO)
    drawn = 0
    for ex_id in course.exercise_ids:
        spec = course.exercise(ex_id)
        for seed in (0, 1):
            params = dict(variant(spec, seed).params)
            svg = plot_for(ex_id, spec.tags, params, solved=True)
            assert (svg is not None) == has_plot(ex_id, spec.tags, params)
            if svg is not None:
                parsed(svg)
                drawn += 1
                pending = plot_for(ex_id, spec.tags, params, solved=False)
                assert pending is None or pending == svg or "?" in pending
    assert set(BY_ID) <= set(course.exercise_ids)
    assert drawn >= 2 * len(BY_ID)


def test_every_figure_is_accessible_svg_and_every_placed_one_exists() -> None:
    """Each chapter module's figures draw well-formed SVG with a text alternative; every
    chapter of the bundled course places at least one; no figure id is an exercise id (the
    `plot` command takes both)."""
    from slamcourse.course.loader import load_course
    from slamcourse.plots.registry import FIGURES
    from tests.conftest import REPO

    course = load_course(REPO)
    placed = {f.id: ch.id for ch in course.chapters for f in ch.figures}
    mine = [f for f in FIGURES if f.split("/")[0] in OWN_CHAPTERS]
    for fig in mine:
        _, title, desc = parsed(FIGURES[fig]())
        assert title and len(desc) > 40, fig
        assert placed.get(fig) == fig.split("/")[0], f"{fig} is not placed in its chapter"
    assert not set(mine) & set(course.exercise_ids)
    for chapter in OWN_CHAPTERS:
        assert any(f.startswith(chapter + "/") for f in placed), chapter


OWN_CHAPTERS = (
    "state", "observation", "association", "drift", "graph", "vision", "factor-graphs",
    "occupancy", "capstone", "se2", "motion", "ekf-slam", "jcbb", "consistency",
    "scan-matching", "orderings", "pose-graph", "intel",
)  # fmt: skip


def test_code_exercises_and_late_chapters_have_pictures() -> None:
    from slamcourse.course.loader import load_course
    from tests.conftest import REPO

    course = load_course(REPO)
    missing_code = []
    late = 0
    with_picture = 0
    for ex_id in course.exercise_ids:
        spec = course.exercise(ex_id)
        if spec.chapter not in OWN_CHAPTERS:
            continue
        has = ex_id in BY_ID or has_plot(ex_id, spec.tags, {})
        if spec.kind == "code" and not has:
            missing_code.append(ex_id)
        if OWN_CHAPTERS.index(spec.chapter) >= OWN_CHAPTERS.index("se2"):
            late += 1
            with_picture += has
    assert missing_code == []
    assert with_picture >= 0.75 * late  # the rest are questions a picture does not help


def _boxes(svg: str) -> list[tuple[float, float, float, float, str]]:
    """Approximate boxes of the text labels (font 12 unless given, anchor start)."""
    from slamcourse.plots.canvas import text_width

    root = ET.fromstring(svg)
    out = []
    for t in root.iter(f"{NS}text"):
        size = float(t.get("font-size", 12))
        x, y, w = float(t.get("x", 0)), float(t.get("y", 0)), text_width(t.text or "", size)
        anchor = t.get("text-anchor", "start")
        x0 = x - w / 2 if anchor == "middle" else x - w if anchor == "end" else x
        out.append((x0, y - size, x0 + w, y + 2, t.text or ""))
    return out


@pytest.mark.parametrize(
    "pose",
    [(2, 3, math.pi / 4, 5, 7), (0, 0, 3.0, -4, -1), (1, 1, -1.2, 1.5, 6), (0, 0, 0, 0.3, 0.2)],
)
def test_observation_labels_never_cover_the_robot_or_each_other(pose: tuple[float, ...]) -> None:
    svg = observation_geometry(*pose)
    root = ET.fromstring(svg)
    robot = next(root.iter(f"{NS}polygon"))  # the robot's triangle
    pts = [tuple(map(float, p.split(","))) for p in (robot.get("points") or "").split()]
    rx0, ry0 = min(p[0] for p in pts), min(p[1] for p in pts)
    rx1, ry1 = max(p[0] for p in pts), max(p[1] for p in pts)
    boxes = _boxes(svg)
    for x0, y0, x1, y1, label in boxes:
        assert x1 <= rx0 or x0 >= rx1 or y1 <= ry0 or y0 >= ry1, f"{label!r} covers the robot"
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            overlap = a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
            assert not overlap, f"{a[4]!r} overlaps {b[4]!r}"


def test_random_walk_sigma_is_a_circle_at_true_scale() -> None:
    """The 1σ circle is drawn round (a close-up at one scale), not squashed into a line by
    the plan view's stretched sideways axis."""
    svg = drift_trajectories(400, sigma=0.05, seed=3)
    root = ET.fromstring(svg)
    circles = [c for c in root.iter(f"{NS}circle") if c.get("stroke-dasharray")]
    assert len(circles) == 1 and float(circles[0].get("r", 0)) > 20
    assert not [e for e in root.iter(f"{NS}ellipse")]


def test_a_figure_is_drawn_once_per_installation_and_redrawn_when_its_code_changes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The learner's cache keeps drawn figures (one runs an optimiser for seconds), keyed by a
    digest of what they are drawn from: a second process reads the file; changed code draws anew."""
    from slamcourse import settings
    from slamcourse.plots import registry

    calls: list[int] = []

    def draw() -> str:
        calls.append(1)
        return f'<svg xmlns="http://www.w3.org/2000/svg"><title>t{len(calls)}</title></svg>'

    monkeypatch.setitem(registry.FIGURES, "test/costly", draw)
    monkeypatch.setattr(settings, "_active_cache", tmp_path)
    first = registry.figure_svg("test/costly")
    assert calls == [1] and first is not None and "t1" in first
    assert list((tmp_path / "figures").glob("*.svg"))
    registry._DRAWN.clear()  # a new process: only the disk remembers
    assert registry.figure_svg("test/costly") == first and calls == [1]
    registry._DRAWN.clear()
    monkeypatch.setattr(registry, "_sources_digest", lambda: "the drawing code changed")
    assert "t2" in (registry.figure_svg("test/costly") or "") and calls == [1, 1]
    registry._DRAWN.pop("test/costly", None)


def test_every_chapter_with_exercises_has_a_figure_and_every_code_exercise_a_picture() -> None:
    """Course-wide (the new chapters included): a teacher's figure in every chapter that has
    exercises, and a picture of the givens for every code exercise (`slamcourse plot ID`)."""
    from slamcourse.course.loader import load_course
    from tests.conftest import REPO

    course = load_course(REPO)
    bare = [ch.id for ch in course.chapters if ch.exercises and not ch.figures]
    assert bare == []
    code = [ex for ex in course.exercise_ids if course.exercise(ex).kind == "code"]
    assert [ex for ex in code if not has_plot(ex, course.exercise(ex).tags, {})] == []
