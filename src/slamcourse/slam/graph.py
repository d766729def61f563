"""Graph SLAM in information form: a pose graph's ``Ω μ = ξ`` and its sparsity.

Poses are 1-D here (``x_0 … x_{n−1}``, metres along a line), so every block is a single number;
with ``d``-dimensional poses each entry becomes a ``d × d`` block and the counts are counts of
blocks. An edge ``(i, j, z, ω)`` says "``x_j − x_i`` was measured as ``z``" with information
``ω`` (1/m², the inverse of the measurement's variance). Its cost ``ω (x_j − x_i − z)²`` adds

    +ω at Ω[i, i] and Ω[j, j],   −ω at Ω[i, j] and Ω[j, i],   −ω z at ξ[i],   +ω z at ξ[j].

A prior ``(k, value, ω₀)`` adds ``ω₀`` at ``Ω[k, k]`` and ``ω₀·value`` at ``ξ[k]``. The estimate
``μ`` minimises the total cost and solves ``Ω μ = ξ``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "chain_edges",
    "cholesky_nonzeros",
    "information_form",
    "information_matrix",
    "nonzero_blocks",
    "solve",
]

Edge = tuple[int, int, float, float]
"""``(i, j, z, ω)``: ``x_j − x_i`` measured as ``z`` metres with information ``ω`` (1/m²)."""
Prior = tuple[int, float, float]
"""``(k, value, ω₀)``: ``x_k`` measured as ``value`` metres with information ``ω₀`` (1/m²)."""


def chain_edges(num_poses: int, z: float = 0.0, omega: float = 1.0) -> list[Edge]:
    """Odometry edges ``k → k + 1`` of a chain of ``num_poses`` poses (``num_poses − 1`` edges)."""
    return [(k, k + 1, z, omega) for k in range(num_poses - 1)]


def information_form(
    num_poses: int, edges: Iterable[Edge], priors: Iterable[Prior] = ()
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(Ω, ξ)``: the information matrix (``n × n``, 1/m²) and vector (``(n,)``, 1/m)."""
    omega = np.zeros((num_poses, num_poses))
    xi = np.zeros(num_poses)
    for i, j, z, w in edges:
        if i == j:
            raise ValueError(f"an edge must join two different poses, got ({i}, {j})")
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
        omega[j, i] -= w
        xi[i] -= w * z
        xi[j] += w * z
    for k, value, w in priors:
        omega[k, k] += w
        xi[k] += w * value
    return omega, xi


def information_matrix(
    num_poses: int, edges: Iterable[Edge], priors: Iterable[Prior] = ()
) -> NDArray[np.float64]:
    """``Ω`` alone (``n × n``, symmetric, positive semi-definite; definite once a prior anchors
    every connected part of the graph)."""
    return information_form(num_poses, edges, priors)[0]


def solve(omega: ArrayLike, xi: ArrayLike) -> NDArray[np.float64]:
    """``μ`` with ``Ω μ = ξ``, through the Cholesky factorisation ``Ω = L Lᵀ``: solve
    ``L y = ξ``, then ``Lᵀ μ = y``. ``Ω`` must be symmetric positive definite (``n × n``)."""
    a = np.asarray(omega, dtype=float)
    b = np.asarray(xi, dtype=float)
    lower = np.linalg.cholesky(a)
    y = np.linalg.solve(lower, b)
    mu: NDArray[np.float64] = np.linalg.solve(lower.T, y)
    return mu


def nonzero_blocks(num_poses: int, pairs: Iterable[tuple[int, int]]) -> int:
    """Nonzero blocks of a pose graph's ``Ω``: one per pose on the diagonal, two mirrored ones per
    distinct linked pair ``(i, j)`` (repeated measurements of a pair share their blocks)."""
    linked = {(min(i, j), max(i, j)) for i, j in pairs if i != j}
    return num_poses + 2 * len(linked)


def cholesky_nonzeros(pattern: ArrayLike, order: Sequence[int] | None = None) -> int:
    """Nonzero entries (blocks) of the Cholesky factor ``L`` of a matrix with the given sparsity
    ``pattern`` (``n × n``, symmetric, truthy where nonzero), eliminating the variables in
    ``order`` (default ``0 … n − 1``). Symbolic elimination: removing a variable links all its
    remaining neighbours (the *fill-in*); ``L`` has one entry per variable and per remaining
    neighbour at the moment each variable is eliminated."""
    adjacency = np.asarray(pattern, dtype=bool)
    n = adjacency.shape[0]
    order = list(range(n)) if order is None else list(order)
    if sorted(order) != list(range(n)):
        raise ValueError("order must be a permutation of 0 … n − 1")
    neighbours = [set(np.flatnonzero(adjacency[v])) - {v} for v in range(n)]
    eliminated: set[int] = set()
    count = 0
    for v in order:
        remaining = neighbours[v] - eliminated
        count += 1 + len(remaining)
        for a in remaining:
            neighbours[a] |= remaining - {a}
        eliminated.add(v)
    return count
