"""Reference answers for chapter ``intel``: optimising the INTEL Research Lab pose graph.

The graph ships with the course in ``data/input_INTEL.g2o`` (attribution in ``data/SOURCE.md``).
Conventions are those of the pose-graph chapter (g2o's): ``e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)``,
``χ² = Σ eᵀ Ω e``, undamped Gauss-Newton with pose 0 fixed; the mathematics lives in
:mod:`slamcourse.slam.posegraph`. Functions whose name starts with ``mistake_`` compute the
answer of a named misconception.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import posegraph as pg

Matrix = NDArray[np.float64]
DATA = Path(__file__).resolve().parent / "data" / "input_INTEL.g2o"
ITERATIONS = 10


@lru_cache(maxsize=1)
def intel() -> pg.PoseGraph:
    return pg.parse_g2o(DATA.read_text(encoding="utf-8"))


def inverse_convention(x: Matrix, edges: Any) -> pg.Stacked:
    """The other common error, ``(x_i⁻¹ ⊕ x_j)⁻¹ ⊕ z = e⁻¹``, with its Jacobians by the chain rule.

    For ``e = (t, φ)``, ``e⁻¹ = (−R(φ)ᵀ t, −φ)``, whose derivative by ``t`` is ``−R(φ)ᵀ`` and by
    ``φ`` is ``−(dR(φ)ᵀ/dφ) t`` (translation) and ``−1`` (angle).
    """
    e, a, b, om = pg.stacked_errors(x, edges)
    c, s = np.cos(e[:, 2]), np.sin(e[:, 2])
    tx, ty = e[:, 0], e[:, 1]
    inv = np.stack([-(c * tx + s * ty), -(-s * tx + c * ty), -e[:, 2]], axis=1)
    d = np.zeros((len(e), 3, 3))
    d[:, 0, 0], d[:, 0, 1], d[:, 1, 0], d[:, 1, 1] = -c, -s, s, -c
    d[:, 0, 2] = -(-s * tx + c * ty)
    d[:, 1, 2] = -(-c * tx - s * ty)
    d[:, 2, 2] = -1.0
    return inv, d @ a, d @ b, om


# --- numeric exercises ------------------------------------------------------------------------


def loop_closures() -> int:
    return sum(1 for e in intel().edges if abs(e.i - e.j) != 1)


def mistake_all_edges() -> int:
    return len(intel().edges)


def degrees_of_freedom() -> int:
    """Error components minus free unknowns: ``3·edges − 3·(poses − 1)``."""
    graph = intel()
    return 3 * len(graph.edges) - 3 * (len(graph.poses) - 1)


def mistake_dof_gauge_ignored() -> int:
    graph = intel()
    return 3 * len(graph.edges) - 3 * len(graph.poses)


def initial_chi2() -> float:
    graph = intel()
    return pg.chi2(graph.poses, graph.edges)


def mistake_initial_chi2_inverse_convention() -> float:
    graph = intel()
    return pg.chi2(graph.poses, graph.edges, inverse_convention)


def mistake_initial_chi2_half() -> float:
    return initial_chi2() / 2


@lru_cache(maxsize=1)
def final_chi2() -> float:
    graph = intel()
    _, history = pg.gauss_newton(graph.poses, graph.edges, ITERATIONS)
    return history[-1]


@lru_cache(maxsize=1)
def mistake_final_chi2_inverse_convention() -> float:
    graph = intel()
    _, history = pg.gauss_newton(graph.poses, graph.edges, ITERATIONS, model=inverse_convention)
    return history[-1]


def mistake_final_chi2_half() -> float:
    return final_chi2() / 2


# --- code: read_edges -------------------------------------------------------------------------


def read_edges(text: str) -> Matrix:
    """One row per ``EDGE_SE2`` line, in file order: ``i, j, dx, dy, dθ`` and the full 3×3
    information matrix row by row (14 numbers)."""
    rows = []
    for line in text.splitlines():
        fields = line.split()
        if fields and fields[0] == "EDGE_SE2":
            om = pg.information_from_upper([float(v) for v in fields[6:12]])
            rows.append([float(v) for v in fields[1:6]] + om.ravel().tolist())
    return np.array(rows, dtype=float).reshape(-1, 14)


def _g2o_text(poses: Matrix, edges: Any, style: int, seed: int) -> str:
    """g2o text in one of several layouts real files use (spacing, blank lines, other records)."""
    rng = np.random.default_rng(seed)
    lines = pg.to_g2o(poses, edges).splitlines()
    if style == 1:  # runs of spaces and tabs between fields, trailing blanks
        lines = [
            "".join(f + str(rng.choice([" ", "  ", "\t", " \t "])) for f in line.split()).rstrip()
            + ("  " if k % 3 == 0 else "")
            for k, line in enumerate(lines)
        ]
    elif style == 2:  # blank lines, a FIX record, vertices after the edges in reverse order
        n = len(poses)
        lines = ["", *lines[n:], "", *reversed(lines[:n]), "FIX 0", ""]
    elif style == 3:  # vertices and edges interleaved, as written by an incremental front end
        n = len(poses)
        vertices, rest = lines[:n], lines[n:]
        lines = [vertices[0]]
        for k in range(1, n):
            lines.append(vertices[k])
            lines.append(rest[k - 1])
        lines.extend(rest[n - 1 :])
    return "\n".join(lines) + "\n"


def g2o_inputs() -> Any:
    """g2o texts of synthetic graphs of 2–15 poses (with correlated information matrices) in
    several layouts."""
    from hypothesis import strategies as st

    def build(seed: int, n: int, loops: int, style: int) -> dict[str, Any]:
        poses, edges = pg.simulate(seed, n, loops if n > 2 else 0)
        return {"text": _g2o_text(poses, edges, style, seed)}

    return st.builds(
        build, st.integers(0, 2**32 - 1), st.integers(2, 15), st.integers(0, 4), st.integers(0, 3)
    )


def mistake_edges_toro_order(text: str) -> Matrix:
    """The six numbers read in TORO's order (Ixx Ixy Iyy Itt Ixt Iyt) instead of g2o's."""
    out = read_edges(text)
    for row in out:
        om = row[5:].reshape(3, 3)
        upper = [om[0, 0], om[0, 1], om[0, 2], om[1, 1], om[1, 2], om[2, 2]]
        ixx, ixy, iyy, itt, ixt, iyt = upper
        row[5:] = np.array([[ixx, ixy, ixt], [ixy, iyy, iyt], [ixt, iyt, itt]]).ravel()
    return out


def mistake_edges_upper_only(text: str) -> Matrix:
    """Only the upper triangle filled: the matrix is not symmetric."""
    out = read_edges(text)
    for row in out:
        om = row[5:].reshape(3, 3)
        row[5:] = np.triu(om).ravel()
    return out


def mistake_edges_diagonal_only(text: str) -> Matrix:
    """Only ``I11, I22, I33`` kept: the correlations are dropped."""
    out = read_edges(text)
    for row in out:
        row[5:] = np.diag(np.diag(row[5:].reshape(3, 3))).ravel()
    return out


# --- code: optimise_g2o -----------------------------------------------------------------------


def optimise_g2o(text: str, iterations: int) -> Matrix:
    """Parse, run ``iterations`` Gauss-Newton steps with pose 0 fixed, return poses seen from 0."""
    graph = pg.parse_g2o(text)
    x, _ = pg.gauss_newton(graph.poses, graph.edges, int(iterations))
    return pg.relative_to_first(x)


@lru_cache(maxsize=4)
def intel_window(first: int, count: int) -> str:
    """The INTEL poses ``first … first+count−1`` and every edge among them, renumbered from 0,
    as g2o text: a piece of the real building with its own loop closures."""
    graph = intel()
    keep = range(first, first + count)
    edges = [
        pg.Edge(e.i - first, e.j - first, e.z, e.information)
        for e in graph.edges
        if e.i in keep and e.j in keep
    ]
    return pg.to_g2o(graph.poses[first : first + count], edges)


def whole_inputs() -> Any:
    """Two windows of the real INTEL graph, then synthetic graphs of 2–25 poses in several
    layouts; 10 or 15 iterations (every graph drawn converges within them)."""
    from hypothesis import strategies as st

    def synthetic(seed: int, n: int, loops: int, style: int, iterations: int) -> dict[str, Any]:
        poses, edges = pg.simulate(seed, n, loops if n > 2 else 0)
        return {"text": _g2o_text(poses, edges, style, seed), "iterations": iterations}

    real = st.sampled_from(
        [
            {"text": intel_window(150, 160), "iterations": 10},
            {"text": intel_window(1060, 160), "iterations": 10},
        ]
    )
    made = st.builds(
        synthetic,
        st.integers(0, 2**32 - 1),
        st.integers(2, 25),
        st.integers(0, 6),
        st.integers(0, 3),
        st.sampled_from([10, 15]),
    )
    return st.one_of(real, made)


def mistake_optimise_absolute(text: str, iterations: int) -> Matrix:
    graph = pg.parse_g2o(text)
    x, _ = pg.gauss_newton(graph.poses, graph.edges, int(iterations))
    return x


def mistake_optimise_toro_order(text: str, iterations: int) -> Matrix:
    """A whole optimisation whose parser read the information in TORO's order."""
    graph = pg.parse_g2o(text)
    edges = []
    for e in graph.edges:
        om = e.information
        ixx, ixy, iyy, itt, ixt, iyt = om[0, 0], om[0, 1], om[0, 2], om[1, 1], om[1, 2], om[2, 2]
        toro = np.array([[ixx, ixy, ixt], [ixy, iyy, iyt], [ixt, iyt, itt]])
        edges.append(pg.Edge(e.i, e.j, e.z, toro))
    x, _ = pg.gauss_newton(graph.poses, edges, int(iterations))
    return pg.relative_to_first(x)


def mistake_optimise_inverse_convention(text: str, iterations: int) -> Matrix:
    graph = pg.parse_g2o(text)
    x, _ = pg.gauss_newton(graph.poses, graph.edges, int(iterations), model=inverse_convention)
    return pg.relative_to_first(x)


def _unwrapped_model(x: Matrix, edges: Any) -> pg.Stacked:
    """This course's error with its angle left unwrapped."""
    e, a, b, om = pg.stacked_errors(x, edges)
    e[:, 2] = [x[edge.j, 2] - x[edge.i, 2] - edge.z[2] for edge in edges]
    return e, a, b, om


def _heading_sign_model(x: Matrix, edges: Any) -> pg.Stacked:
    """This course's error with the top of A's third column negated."""
    e, a, b, om = pg.stacked_errors(x, edges)
    a[:, :2, 2] *= -1
    return e, a, b, om


def mistake_optimise_no_wrap(text: str, iterations: int) -> Matrix:
    graph = pg.parse_g2o(text)
    x, _ = pg.gauss_newton(graph.poses, graph.edges, int(iterations), model=_unwrapped_model)
    return pg.relative_to_first(x)


def mistake_optimise_jacobian_sign(text: str, iterations: int) -> Matrix:
    graph = pg.parse_g2o(text)
    x, _ = pg.gauss_newton(graph.poses, graph.edges, int(iterations), model=_heading_sign_model)
    return pg.relative_to_first(x)


def mistake_optimise_not_optimised(text: str, iterations: int) -> Matrix:
    return pg.relative_to_first(pg.parse_g2o(text).poses)


def before_after_demo() -> tuple[list[list[float]], list[list[float]]]:
    """The INTEL trajectory before and after optimisation (for pictures; not an exercise)."""
    before, after = pg.before_after(DATA.read_text(encoding="utf-8"), ITERATIONS)
    return before.tolist(), after.tolist()


# --- code: intel_chi2 (the whole graph) -------------------------------------------------------


@lru_cache(maxsize=16)
def _chi2_after(text: str, iterations: int, model: pg.ErrorModel | None = None) -> float:
    """χ² (under ``model``'s error) after ``iterations`` Gauss-Newton steps, pose 0 fixed."""
    graph = pg.parse_g2o(text)
    _, history = pg.gauss_newton(graph.poses, graph.edges, int(iterations), model=model)
    return history[-1]


def intel_chi2(text: str, iterations: int) -> float:
    """Parse a g2o text, run ``iterations`` undamped Gauss-Newton steps with pose 0 fixed and
    return the final ``χ² = Σ eᵀ Ω e`` (dimensionless)."""
    return _chi2_after(text, int(iterations))


def intel_whole_input() -> Any:
    """Exactly one input: the whole INTEL graph, as shipped, with ten iterations."""
    from hypothesis import strategies as st

    return st.just({"text": DATA.read_text(encoding="utf-8"), "iterations": ITERATIONS})


def mistake_chi2_no_wrap(text: str, iterations: int) -> float:
    """Angular errors never wrapped (neither in the steps nor in the χ² reported)."""
    return _chi2_after(text, int(iterations), _unwrapped_model)


def mistake_chi2_jacobian_sign(text: str, iterations: int) -> float:
    """The top of A's third column negated: the steps go elsewhere; the χ² itself is right."""
    return _chi2_after(text, int(iterations), _heading_sign_model)


def mistake_chi2_inverse_convention(text: str, iterations: int) -> float:
    """The inverted error ``(x_i⁻¹ ⊕ x_j)⁻¹ ⊕ z`` optimised and reported."""
    return _chi2_after(text, int(iterations), inverse_convention)


def mistake_chi2_half(text: str, iterations: int) -> float:
    """GTSAM's printed error, ``½ Σ eᵀ Ω e``."""
    return intel_chi2(text, iterations) / 2


def mistake_chi2_not_optimised(text: str, iterations: int) -> float:
    """The χ² of the initial guess: the steps never reached the poses."""
    return _chi2_after(text, 0)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def _parses(text: str) -> pg.PoseGraph | None:
    """The graph of a g2o text whose vertex ids run from 0 to n − 1, or None."""
    try:
        graph = pg.parse_g2o(text)
    except Exception:  # not a g2o text the prompts describe
        return None
    n = len(graph.poses)
    if n < 2 or any(not (0 <= e.i < n and 0 <= e.j < n) for e in graph.edges):
        return None
    return graph


def optimise_valid(text: str, iterations: int) -> bool:
    """``optimise_g2o``'s domain: a g2o text of a graph the prompt describes, and an iteration
    count within which it converges (or 0: the initial guess). Where Gauss-Newton has not
    converged, the iterate depends on the gauge a correct method chooses (pose 0 fixed, or a
    strong prior on it), which the prompt does not fix."""
    graph = _parses(text)
    if graph is None or not 0 <= iterations <= 30:
        return False
    if iterations == 0:
        return True
    x, _ = pg.gauss_newton(graph.poses, graph.edges, int(iterations))
    y, _ = pg.gauss_newton(x, graph.edges, 3)
    return bool(np.max(np.abs(pg.relative_to_first(x) - pg.relative_to_first(y))) < 1e-8)


def whole_valid(text: str, iterations: int) -> bool:
    """``intel_chi2``'s domain: a g2o text and 0–30 iterations; a graph as large as INTEL (more
    than 200 poses) is run for the 10 iterations the prompt states."""
    graph = _parses(text)
    if graph is None or not 0 <= iterations <= 30:
        return False
    return len(graph.poses) <= 200 or iterations == ITERATIONS
