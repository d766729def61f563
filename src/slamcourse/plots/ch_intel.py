"""Chapter ``intel``: the INTEL Research Lab pose graph before and after optimisation."""

from __future__ import annotations

import functools

import numpy as np

from slamcourse.plots.canvas import BLUE, MUTED, ORANGE, Plane
from slamcourse.plots.picture import Figure, Picture, answer, given
from slamcourse.plots.svg import num
from slamcourse.slam import posegraph as pg

ITERATIONS = 10


@functools.cache
def intel_graph() -> pg.PoseGraph:
    """The INTEL graph shipped with the bundled course (exercises/intel/data)."""
    from slamcourse.course.locate import bundled_course_root

    path = bundled_course_root() / "exercises" / "intel" / "data" / "input_INTEL.g2o"
    return pg.parse_g2o(path.read_text(encoding="utf-8"))


@functools.cache
def _optimised() -> tuple[np.ndarray, tuple[float, ...]]:
    graph = intel_graph()
    after, history = pg.gauss_newton(graph.poses, graph.edges, ITERATIONS)
    return after, tuple(history)


def intel_figure(*, optimised: bool = True, loops: bool = False) -> str:
    """The initial INTEL trajectory (dead reckoning from odometry) and, with ``optimised``,
    the trajectory after Gauss-Newton; ``loops`` draws the loop-closure edges."""
    graph = intel_graph()
    before = graph.poses
    series = [("initial guess (odometry)", before, ORANGE, "4 2" if optimised else None)]
    history: tuple[float, ...] = ()
    if optimised:
        after, history = _optimised()
        series.append((f"after {ITERATIONS} Gauss-Newton steps", after, BLUE, None))
    pts = [(float(x), float(y)) for _, est, _, _ in series for x, y, _ in est]
    plane = Plane(pts, width=560, height=460, pad=24, top=60)
    closures = [e for e in graph.edges if abs(e.i - e.j) != 1]
    if loops:
        est = series[-1][1]
        for e in closures:
            a, b = est[e.i], est[e.j]
            plane.body.append(
                f'<line x1="{plane.sx(a[0]):.1f}" y1="{plane.sy(a[1]):.1f}" '
                f'x2="{plane.sx(b[0]):.1f}" y2="{plane.sy(b[1]):.1f}" stroke="{MUTED}" '
                'stroke-width="0.5" stroke-opacity="0.5"/>'
            )
    for _, est, colour, dash in series:
        plane.path([(float(x), float(y)) for x, y, _ in est], colour=colour, dash=dash, width=1.0)
    legend = [(name, colour, dash or "") for name, _, colour, dash in series]
    if loops:
        legend.append(("loop-closure edges", MUTED, ""))
    n = len(before)
    desc = (
        f"The INTEL Research Lab graph: {n} poses, chained by odometry edges and tied across the "
        "building by loop closures"
        + (" (grey)" if loops else "")
        + ". The initial guess, chained from odometry, drifts so far that the "
        "corridors of the building are drawn many times over, crossing each other"
        + (
            f"; after {ITERATIONS} Gauss-Newton steps with pose 0 fixed the corridors line up "
            f"and χ² falls by a factor of about {num(history[0] / history[-1], 2)}."
            if optimised
            else "."
        )
    )
    title = "The INTEL graph before and after optimisation" if optimised else "The INTEL graph"
    return plane.svg(title, desc, legend)


FIGURES: dict[str, Figure] = {
    "intel/before-after": intel_figure,
    "intel/initial-guess": lambda: intel_figure(optimised=False, loops=True),
}

PICTURES: dict[str, Picture] = {
    "intel/loop-closures": given(lambda p: intel_figure(optimised=False, loops=True)),
    "intel/initial-chi2": given(lambda p: intel_figure(optimised=False)),
    "intel/final-chi2": answer(lambda p: intel_figure()),
    "intel/whole-graph": given(lambda p: intel_figure(optimised=False)),
    # the graph these functions read and optimise (their small examples are in the prompts)
    "intel/read-edges": given(lambda p: intel_figure(optimised=False, loops=True)),
    "intel/optimise-g2o": given(lambda p: intel_figure(optimised=False)),
}
