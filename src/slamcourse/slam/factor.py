"""Factor graphs and variable elimination: the mathematics of chapter 7.

A graph here is the *variable* graph of a factor graph: nodes ``0 … n−1`` are variables and two
are linked when some factor involves both. Eliminating a variable (one step of sparse Cholesky or
QR factorisation) links every pair of its remaining neighbours; each link that was not already
there is a *fill-in* edge.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from itertools import combinations

Edge = tuple[int, int]


def adjacency(n: int, edges: Iterable[Sequence[int]]) -> list[set[int]]:
    """Neighbour sets of the undirected graph with nodes ``0 … n−1`` and ``edges``."""
    adj: list[set[int]] = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    return adj


def eliminate(n: int, edges: Iterable[Sequence[int]], order: Sequence[int]) -> list[Edge]:
    """The fill-in edges ``(a, b)``, ``a < b``, created by eliminating the nodes in ``order``,
    in the order they appear. Eliminated nodes leave the graph."""
    adj = adjacency(n, edges)
    created: list[Edge] = []
    for v in order:
        for a, b in combinations(sorted(adj[v]), 2):
            if b not in adj[a]:
                adj[a].add(b)
                adj[b].add(a)
                created.append((a, b))
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return created


def fill_in(n: int, edges: Iterable[Sequence[int]], order: Sequence[int]) -> int:
    """Number of fill-in edges of the elimination ``order``."""
    return len(eliminate(n, edges, order))


def chain(n: int) -> list[Edge]:
    """Edges of the chain ``x0 — x1 — … — x(n−1)`` (odometry between consecutive poses)."""
    return [(k, k + 1) for k in range(n - 1)]


def star(leaves: int) -> list[Edge]:
    """Edges of a star: centre ``0`` linked to the leaves ``1 … leaves``."""
    return [(0, k) for k in range(1, leaves + 1)]


def factor_and_variable_counts(
    num_poses: int, num_landmarks: int, sightings: int
) -> tuple[int, int]:
    """``(factors, variables)`` of a pose chain with a prior, odometry between consecutive poses,
    and each landmark observed from ``sightings`` poses."""
    factors = 1 + (num_poses - 1) + num_landmarks * sightings
    return factors, num_poses + num_landmarks


def constraint_dof(
    num_poses: int, num_observations: int, pose_dof: int = 3, landmark_dof: int = 2
) -> int:
    """Scalar equations of the factors: a prior and ``num_poses − 1`` odometry factors of
    ``pose_dof`` each, and ``num_observations`` observations of ``landmark_dof`` each."""
    return num_poses * pose_dof + num_observations * landmark_dof


def unknown_dof(
    num_poses: int, num_landmarks: int, pose_dof: int = 3, landmark_dof: int = 2
) -> int:
    """Scalar unknowns: ``pose_dof`` per pose and ``landmark_dof`` per landmark."""
    return num_poses * pose_dof + num_landmarks * landmark_dof
