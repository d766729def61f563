"""Reference code for chapter ``graph``: the information form of a 1-D pose graph.

Poses are scalars ``x_0 … x_{n−1}`` (metres along a line). A constraint (edge) between poses
``i`` and ``j`` with information ``ω`` (1/m², the inverse of its variance) contributes

    +ω at Ω[i, i] and Ω[j, j],   −ω at Ω[i, j] and Ω[j, i]

to the information matrix ``Ω``. A prior of information ``ω₀`` on pose ``k`` adds ``ω₀`` to
``Ω[k, k]`` only. The estimate ``μ`` solves the linear system ``Ω μ = ξ``.

Every exercise function takes the exercise's parameters (or a code exercise's arguments) as
keyword arguments. Functions whose name starts with ``mistake_`` are wrong implementations or
wrong answers of a named misconception.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

Edge = tuple[int, int, float]


# --- the information matrix -----------------------------------------------------------------


def build_omega(n: int, edges: Sequence[Edge]) -> NDArray[np.float64]:
    """``Ω`` (n × n) of a 1-D pose graph with the given ``(i, j, ω)`` edges."""
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
        omega[j, i] -= w
    return omega


def omega_inputs() -> Any:
    """Hypothesis strategy for ``build_omega``: 1–30 poses and up to 40 edges with i ≠ j and
    information ω in [0.01, 10⁴] 1/m² (standard deviations from 10 m down to 1 cm).

    Pairs may repeat (two measurements of the same relative motion) and either end may be the
    larger index (a loop closure written from the newer pose back to the older one).
    """
    from hypothesis import strategies as st

    def for_size(n: int) -> Any:
        if n == 1:
            return st.fixed_dictionaries({"n": st.just(1), "edges": st.just([])})
        pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(
            lambda p: p[0] != p[1])
        weight = st.floats(0.01, 1e4, allow_nan=False, allow_infinity=False)
        edge = st.builds(lambda p, w: (p[0], p[1], w), pair, weight)
        return st.fixed_dictionaries({"n": st.just(n), "edges": st.lists(edge, max_size=40)})

    return st.integers(1, 30).flatmap(for_size)


def mistake_omega_no_off_diagonal(n: int, edges: Sequence[Edge]) -> NDArray[np.float64]:
    """Only the diagonal entries: the −ω coupling the two poses is missing."""
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
    return omega


def mistake_omega_plus_off_diagonal(n: int, edges: Sequence[Edge]) -> NDArray[np.float64]:
    """+ω instead of −ω at (i, j) and (j, i)."""
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] += w
        omega[j, i] += w
    return omega


def mistake_omega_upper_only(n: int, edges: Sequence[Edge]) -> NDArray[np.float64]:
    """Only the upper triangle gets the −ω: the matrix is not symmetric."""
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[min(i, j), max(i, j)] -= w
    return omega


def mistake_omega_assigned(n: int, edges: Sequence[Edge]) -> NDArray[np.float64]:
    """``=`` instead of ``+=``: each edge overwrites what earlier edges put in the same cells."""
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] = w
        omega[j, j] = w
        omega[i, j] = -w
        omega[j, i] = -w
    return omega


# --- solving the information form -----------------------------------------------------------


def solve_information(omega: Sequence[Sequence[float]],
                      xi: Sequence[float]) -> NDArray[np.float64]:
    """``μ`` with ``Ω μ = ξ`` (``Ω`` symmetric positive definite, n × n; ``ξ`` length n)."""
    return np.linalg.solve(np.asarray(omega, dtype=float), np.asarray(xi, dtype=float))


def information_system_inputs() -> Any:
    """Hypothesis strategy for ``solve_information``: a connected 1-D pose graph with a prior.

    1–15 poses; a chain of odometry edges and up to 3 extra (loop-closure) edges with
    information in [0.5, 100] 1/m² (standard deviations from 1.4 m down to 10 cm), and a prior on
    pose 0 with information in [1, 1000] 1/m². ``Ω`` is then symmetric positive definite with a
    condition number below about 10⁶. ``ξ = Ω μ`` for poses ``μ`` in [−100, 100] m. ``omega`` is
    passed as a list of rows, ``xi`` as a list.
    """
    from hypothesis import strategies as st

    weight = st.floats(0.5, 100.0, allow_nan=False, allow_infinity=False)
    position = st.floats(-100.0, 100.0, allow_nan=False, allow_infinity=False)

    @st.composite
    def system(draw: Any) -> dict[str, Any]:
        n = draw(st.integers(1, 15))
        edges = [(k, k + 1, draw(weight)) for k in range(n - 1)]
        if n > 2:
            pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(
                lambda p: abs(p[0] - p[1]) > 1)
            edges += [(i, j, draw(weight)) for i, j in draw(st.lists(pair, max_size=3))]
        omega = build_omega(n, edges)
        omega[0, 0] += draw(st.floats(1.0, 1000.0, allow_nan=False, allow_infinity=False))
        mu = np.array(draw(st.lists(position, min_size=n, max_size=n)))
        return {"omega": omega.tolist(), "xi": (omega @ mu).tolist()}

    return system()


def mistake_solve_diagonal_only(omega: Sequence[Sequence[float]],
                                xi: Sequence[float]) -> NDArray[np.float64]:
    """``ξ_i / Ω_ii``: ignores the off-diagonal couplings (exact only for a diagonal Ω)."""
    return np.asarray(xi, dtype=float) / np.diag(np.asarray(omega, dtype=float))


def mistake_solve_multiplied(omega: Sequence[Sequence[float]],
                             xi: Sequence[float]) -> NDArray[np.float64]:
    """``Ω ξ``: multiplied by Ω instead of solving (multiplying by Ω⁻¹)."""
    return np.asarray(omega, dtype=float) @ np.asarray(xi, dtype=float)


# --- numeric exercises: the lesson's 3-pose loop and a long chain ---------------------------


def loop_graph_omega(num_poses: int, prior: float, odo_info: float,
                     loop_info: float) -> NDArray[np.float64]:
    """``Ω`` of a chain ``0 → 1 → … → n−1`` (odometry, information ``odo_info``), a loop
    closure ``0 → n−1`` (``loop_info``) and a prior ``prior`` on pose 0."""
    edges = [(k, k + 1, odo_info) for k in range(num_poses - 1)]
    edges.append((0, num_poses - 1, loop_info))
    omega = build_omega(num_poses, edges)
    omega[0, 0] += prior
    return omega


def omega_nonzero_count(num_poses: int) -> int:
    """Nonzero entries of ``Ω`` for a chain with one loop closure from the last pose to the first
    and a prior on the first (``num_poses ≥ 3``, so the loop is not an odometry pair)."""
    return int(np.count_nonzero(loop_graph_omega(num_poses, 10.0, 1.0, 1.0)))


def mistake_nonzeros_no_loop(num_poses: int) -> int:
    """The loop closure's two off-diagonal entries forgotten: a tridiagonal count."""
    return num_poses + 2 * (num_poses - 1)


def mistake_nonzeros_one_triangle(num_poses: int) -> int:
    """Each edge's off-diagonal entry counted once, as if Ω were not symmetric."""
    return num_poses + (num_poses - 1) + 1


def omega_first_diagonal(prior: float, odo_info: float, loop_info: float) -> float:
    """``Ω[0, 0]`` of the lesson's 3-pose loop: the prior plus every edge touching pose 0."""
    return float(loop_graph_omega(3, prior, odo_info, loop_info)[0, 0])


def mistake_first_diagonal_no_prior(prior: float, odo_info: float, loop_info: float) -> float:
    """The prior left out."""
    return odo_info + loop_info


def mistake_first_diagonal_no_loop(prior: float, odo_info: float, loop_info: float) -> float:
    """The loop closure left out."""
    return prior + odo_info


def loop_graph_estimate(prior: float, xi0: float, xi1: float, xi2: float,
    **_measurements: float) -> NDArray[np.float64]:
    """``μ`` solving ``Ω μ = ξ`` for the lesson's 3-pose loop (all edges ω = 1)."""
    return solve_information(loop_graph_omega(3, prior, 1.0, 1.0).tolist(), [xi0, xi1, xi2])


def mistake_estimate_diagonal_only(prior: float, xi0: float, xi1: float,
                                   xi2: float,
    **_measurements: float) -> NDArray[np.float64]:
    """``ξ_i / Ω_ii``: the couplings between the poses ignored."""
    omega = loop_graph_omega(3, prior, 1.0, 1.0)
    return np.array([xi0, xi1, xi2]) / np.diag(omega)


def chain_block_percent(num_poses: int) -> float:
    """Percentage of the ``N × N`` blocks of a chain's ``Ω`` that are nonzero: N diagonal blocks
    and two mirrored blocks per odometry edge, ``(N + 2(N − 1)) / N²``."""
    blocks = num_poses + 2 * (num_poses - 1)
    return 100.0 * blocks / num_poses**2


def mistake_chain_one_side(num_poses: int) -> float:
    """Each edge's off-diagonal block counted once: ``(N + (N − 1)) / N²``."""
    return 100.0 * (2 * num_poses - 1) / num_poses**2


def mistake_chain_fraction(num_poses: int) -> float:
    """The fraction, not the percentage."""
    return chain_block_percent(num_poses) / 100.0


# --- more of the lesson's questions (computed by slamcourse.slam.graph) ----------------------


def _loop_omega(prior: float, odo_info: float, loop_info: float) -> NDArray[np.float64]:
    """``Ω`` of the lesson's 3-pose loop: odometry 0→1, 1→2, loop closure 0→2, prior on 0."""
    from slamcourse.slam.graph import information_matrix

    edges = [(0, 1, 0.0, odo_info), (1, 2, 0.0, odo_info), (0, 2, 0.0, loop_info)]
    return information_matrix(3, edges, [(0, 0.0, prior)])


def loop_omega_matrix(prior: float, odo_info: float, loop_info: float) -> NDArray[np.float64]:
    """The whole ``Ω`` (3 × 3) of the lesson's 3-pose loop."""
    return _loop_omega(prior, odo_info, loop_info)


def mistake_loop_omega_no_prior(
    prior: float, odo_info: float, loop_info: float
) -> NDArray[np.float64]:
    """The prior left out of ``Ω[0, 0]``."""
    return _loop_omega(0.0, odo_info, loop_info)


def mistake_loop_omega_plus(prior: float, odo_info: float, loop_info: float) -> NDArray[np.float64]:
    """``+ω`` instead of ``−ω`` off the diagonal."""
    omega = _loop_omega(prior, odo_info, loop_info)
    return np.abs(omega)


def mistake_loop_omega_no_loop(
    prior: float, odo_info: float, loop_info: float
) -> NDArray[np.float64]:
    """The loop closure left out: a tridiagonal ``Ω``."""
    return _loop_omega(prior, odo_info, 0.0) + 0.0  # + 0.0 turns −0.0 into 0.0


def loop_first_estimate(prior: float, xi0: float, xi1: float, xi2: float,
    **_measurements: float) -> float:
    """``μ₀`` of the lesson's 3-pose loop (all edges ω = 1), from a Cholesky solve."""
    from slamcourse.slam.graph import solve

    return float(solve(_loop_omega(prior, 1.0, 1.0), [xi0, xi1, xi2])[0])


def mistake_first_estimate_diagonal(prior: float, xi0: float, xi1: float, xi2: float,
    **_measurements: float) -> float:
    """``ξ₀ / Ω₀₀``: the couplings to the other poses ignored."""
    return xi0 / (prior + 2.0)


def mistake_first_estimate_prior_only(prior: float, xi0: float, xi1: float, xi2: float,
    **_measurements: float) -> float:
    """``ξ₀ / ω₀``: ξ₀ divided by the prior's information alone."""
    return xi0 / prior


def chain_nonzero_blocks(num_poses: int, loops: int = 0) -> int:
    """Nonzero blocks of the ``Ω`` of a chain of ``num_poses`` poses with ``loops`` loop closures,
    each between two poses not already linked: ``N + 2(N − 1) + 2L``."""
    from slamcourse.slam.graph import nonzero_blocks

    odometry = [(k, k + 1) for k in range(num_poses - 1)]
    closures = [(k, k + 2) for k in range(loops)]  # any pairs not linked by odometry
    return nonzero_blocks(num_poses, odometry + closures)


def mistake_chain_blocks_one_side(num_poses: int, loops: int = 0) -> int:
    """Each edge's off-diagonal block counted once: ``N + (N − 1) + L``."""
    return num_poses + (num_poses - 1) + loops


def mistake_chain_blocks_no_diagonal(num_poses: int, loops: int = 0) -> int:
    """Only the off-diagonal blocks: ``2(N − 1) + 2L``."""
    return 2 * (num_poses - 1) + 2 * loops


def mistake_chain_entries(num_poses: int, loops: int = 0, block: int = 3) -> int:
    """Nonzero *entries* (``block²`` per block) where blocks were asked for."""
    return block * block * chain_nonzero_blocks(num_poses, loops)


def mistake_loop_blocks_four(num_poses: int, loops: int) -> int:
    """Four new blocks per loop closure, as if its two diagonal blocks were new too."""
    return chain_nonzero_blocks(num_poses) + 4 * loops


def mistake_loop_blocks_ignored(num_poses: int, loops: int) -> int:
    """The loop closures forgotten: the plain chain's count."""
    return chain_nonzero_blocks(num_poses)


def chain_covariance_nonzeros(num_poses: int) -> int:
    """Nonzero entries of ``Σ = Ω⁻¹`` for a 1-D chain with a prior on pose 0: all ``N²``,
    counted on the actual inverse (entries above 1e-12 in size)."""
    from slamcourse.slam.graph import chain_edges, information_matrix

    omega = information_matrix(num_poses, chain_edges(num_poses), [(0, 0.0, 1.0)])
    return int(np.count_nonzero(np.abs(np.linalg.inv(omega)) > 1e-12))


def mistake_covariance_like_omega(num_poses: int) -> int:
    """``Σ`` taken to be as sparse as ``Ω``: ``3N − 2``, the tridiagonal count."""
    return 3 * num_poses - 2


def _ring_pattern(num_poses: int) -> NDArray[np.bool_]:
    """Sparsity of ``Ω`` for a chain ``0 → … → N−1`` closed by a loop closure ``N−1 → 0``."""
    from slamcourse.slam.graph import chain_edges, information_matrix

    edges = [*chain_edges(num_poses), (0, num_poses - 1, 0.0, 1.0)]
    pattern: NDArray[np.bool_] = information_matrix(num_poses, edges) != 0
    return pattern


def ring_factor_nonzeros(num_poses: int) -> int:
    """Nonzeros of the Cholesky factor ``L`` of the ring, poses eliminated in chain order."""
    from slamcourse.slam.graph import cholesky_nonzeros

    return cholesky_nonzeros(_ring_pattern(num_poses))


def mistake_ring_no_fill(num_poses: int) -> int:
    """``L`` taken to have exactly the nonzeros of the lower triangle of ``Ω``: ``2N``."""
    return int(np.count_nonzero(np.tril(_ring_pattern(num_poses))))


def mistake_ring_chain_only(num_poses: int) -> int:
    """The loop closure forgotten: a chain's factor, ``2N − 1``."""
    return 2 * num_poses - 1


def mistake_ring_dense(num_poses: int) -> int:
    """A full lower triangle, ``N(N + 1)/2``."""
    return num_poses * (num_poses + 1) // 2


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def omega_valid(n: int, edges: Sequence[Edge]) -> bool:
    """``build_omega``'s domain: 1–30 poses, at most 40 edges ``(i, j, ω)`` between two
    different poses with ``ω`` in [0.01, 10⁴] 1/m²."""
    if not 1 <= n <= 30 or len(edges) > 40 or isinstance(edges, np.ndarray):
        return False  # the prompt: a list or a tuple of edges
    for e in edges:
        if len(e) != 3:
            return False
        i, j, w = e
        if isinstance(i, float) or isinstance(j, float):
            return False
        if i == j or not (0 <= i < n and 0 <= j < n) or not 0.01 <= w <= 1e4:
            return False
    return True


def information_system_valid(omega: Sequence[Sequence[float]], xi: Sequence[float]) -> bool:
    """``solve_information``'s domain: ``Ω`` symmetric positive definite, 1–15 poses, condition
    number below 10⁷ (a chain with a prior stays below about 10⁶), ``ξ`` of the same length."""
    a = np.asarray(omega, dtype=float)
    b = np.asarray(xi, dtype=float)
    if a.ndim != 2 or a.shape[0] != a.shape[1] or not 1 <= a.shape[0] <= 15:
        return False
    if b.shape != (a.shape[0],) or not np.allclose(a, a.T, rtol=0, atol=1e-12):
        return False
    try:
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return False
    return bool(np.linalg.cond(a) < 1e7 and np.all(np.isfinite(b)))


# --- one edge's contribution, expanded (issue 16) ---------------------------------------------


def edge_omega(i: int, j: int, w: float, d: float, n: int = 4) -> list[list[float]]:
    """What the edge ``ω (x_j − x_i − d)²`` adds to ``Ω`` (n × n): half the second derivative
    of the square, ``+ω`` at (i, i) and (j, j), ``−ω`` at (i, j) and (j, i)."""
    i, j = int(i), int(j)
    out = np.zeros((int(n), int(n)))
    out[i, i] += w
    out[j, j] += w
    out[i, j] -= w
    out[j, i] -= w
    return out.tolist()


def edge_xi(i: int, j: int, w: float, d: float, n: int = 4) -> list[float]:
    """What the edge adds to ``ξ`` (n,): minus half the gradient of the square at ``x = 0``,
    ``−ω d`` at ``i`` and ``+ω d`` at ``j``."""
    out = np.zeros(int(n))
    out[int(i)] -= w * d
    out[int(j)] += w * d
    return out.tolist()


def edge_cost_gradient(i: int, j: int, w: float, d: float, x: Sequence[float]) -> list[float]:
    """``∇ ω (x_j − x_i − d)²`` at ``x``: for checking ``Ω x − ξ`` = half of it."""
    r = float(x[int(j)]) - float(x[int(i)]) - d
    g = np.zeros(len(x))
    g[int(i)] -= 2 * w * r
    g[int(j)] += 2 * w * r
    return g.tolist()


def mistake_edge_omega_doubled(i: int, j: int, w: float, d: float, n: int = 4) -> list[list[float]]:
    """The factor 2 of the derivative kept: ``±2ω``."""
    return (2 * np.array(edge_omega(i, j, w, d, n))).tolist()


def mistake_edge_omega_plus(i: int, j: int, w: float, d: float, n: int = 4) -> list[list[float]]:
    """``+ω`` off the diagonal as well."""
    return np.abs(np.array(edge_omega(i, j, w, d, n))).tolist()


def mistake_edge_omega_one_corner(
    i: int, j: int, w: float, d: float, n: int = 4
) -> list[list[float]]:
    """The cross term ``−2ω x_i x_j`` written into one corner, ``(i, j)``, instead of shared."""
    out = np.zeros((int(n), int(n)))
    out[int(i), int(i)] = w
    out[int(j), int(j)] = w
    out[int(i), int(j)] = -2 * w
    return out.tolist()


def mistake_edge_xi_signs(i: int, j: int, w: float, d: float, n: int = 4) -> list[float]:
    """``+ω d`` at ``i`` and ``−ω d`` at ``j``: the signs swapped."""
    return (-np.array(edge_xi(i, j, w, d, n))).tolist()


def mistake_edge_xi_no_information(i: int, j: int, w: float, d: float, n: int = 4) -> list[float]:
    """``∓d`` without the information ``ω``."""
    return (np.array(edge_xi(i, j, w, d, n)) / w).tolist()


def mistake_edge_xi_target_only(i: int, j: int, w: float, d: float, n: int = 4) -> list[float]:
    """Only ``+ω d`` at ``j``: the edge's own start forgotten."""
    out = np.zeros(int(n))
    out[int(j)] = w * d
    return out.tolist()
