"""Reference code for chapter ``orderings``: sparse solves, elimination orders and fill-in.

Graphs are on the variables ``0 … n−1``; ``edges`` is a list of pairs ``[i, j]`` (``i ≠ j``; a pair
may repeat or come in either direction). An elimination ``order`` is a permutation of
``0 … n−1``. The mathematics lives in :mod:`slamcourse.slam.orderings`. The INTEL graph is the one
the intel chapter ships (``exercises/intel/data/input_INTEL.g2o``, attribution in its SOURCE.md).

Functions whose name starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

from slamcourse.slam import orderings as so

INTEL = Path(__file__).resolve().parent.parent / "intel" / "data" / "input_INTEL.g2o"


@lru_cache(maxsize=1)
def intel() -> tuple[int, list[so.Edge]]:
    return so.g2o_pose_edges(INTEL.read_text(encoding="utf-8"))


@lru_cache(maxsize=1)
def intel_figures() -> dict[str, int]:
    n, edges = intel()
    natural = list(range(n))
    md = so.min_degree_order(n, edges)
    nat_counts = so.column_counts(n, edges, natural)
    md_counts = so.column_counts(n, edges, md)
    return {
        "poses": n,
        "edges": len(so.unique_edges(edges)),
        "fill_natural": so.fill_count(n, edges, natural),
        "fill_md": so.fill_count(n, edges, md),
        "nnz_natural": so.factor_nonzeros(n, edges, natural),
        "nnz_md": so.factor_nonzeros(n, edges, md),
        "cost_natural": sum(c * c for c in nat_counts),
        "cost_md": sum(c * c for c in md_counts),
    }


# --- bundle adjustment: landmarks first (the Schur complement) ---------------------------------


def ba_edges(poses: int, landmarks: int) -> list[so.Edge]:
    """Poses ``0 … P−1`` in an odometry chain; landmarks ``P … P+L−1``, each seen from every
    pose."""
    return [*so.chain(poses), *((p, poses + k) for k in range(landmarks) for p in range(poses))]


def landmarks_first(poses: int, landmarks: int) -> int:
    order = [*range(poses, poses + landmarks), *range(poses)]
    return so.fill_count(poses + landmarks, ba_edges(poses, landmarks), order)


def mistake_landmarks_first_all_pairs(poses: int, landmarks: int) -> int:
    """Every pair of poses counted, the odometry pairs included."""
    return poses * (poses - 1) // 2


def mistake_landmarks_first_per_landmark(poses: int, landmarks: int) -> int:
    """The first landmark's fill counted once per landmark."""
    return landmarks * landmarks_first(poses, landmarks)


def mistake_landmarks_first_poses_first(poses: int, landmarks: int) -> int:
    """The fill of the other order: the poses first, then the landmarks."""
    order = [*range(poses), *range(poses, poses + landmarks)]
    return so.fill_count(poses + landmarks, ba_edges(poses, landmarks), order)


# --- chain with one loop closure ----------------------------------------------------------------


def chain_loop_edges(n: int, a: int, b: int) -> list[so.Edge]:
    return [*so.chain(n), (a, b)]


def chain_loop_natural(n: int, a: int, b: int) -> int:
    return so.fill_count(n, chain_loop_edges(n, a, b), list(range(n)))


def chain_loop_first(n: int, a: int, b: int) -> int:
    """Fill when pose ``b`` (a loop-closure end, three neighbours) goes first, then the rest in order."""
    order = [b, *(v for v in range(n) if v != b)]
    return so.fill_count(n, chain_loop_edges(n, a, b), order)


def mistake_chain_loop_whole(n: int, a: int, b: int) -> int:
    """The loop treated as closing the whole chain: a cycle of ``n`` poses."""
    return n - 3


def mistake_chain_loop_cycle_length(n: int, a: int, b: int) -> int:
    """One fill edge per pose strictly inside the loop, ``b − a − 1``."""
    return b - a - 1


def mistake_chain_first_no_later(n: int, a: int, b: int) -> int:
    """Only the fill of the first elimination counted (3), the fill it causes later forgotten."""
    return so.fill_count(n, chain_loop_edges(n, a, b), [b])


# --- INTEL ---------------------------------------------------------------------------------------


def intel_nonzero_ratio(**_: int) -> float:
    f = intel_figures()
    return f["nnz_natural"] / f["nnz_md"]


def mistake_intel_fill_ratio(**_: int) -> float:
    f = intel_figures()
    return f["fill_natural"] / f["fill_md"]


def mistake_intel_no_diagonal(**_: int) -> float:
    f = intel_figures()
    return (f["nnz_natural"] - f["poses"]) / (f["nnz_md"] - f["poses"])


def intel_cost_ratio(**_: int) -> float:
    f = intel_figures()
    return f["cost_natural"] / f["cost_md"]


def intel_md_nonzeros(**_: int) -> int:
    f = intel_figures()
    return f["nnz_md"]


def mistake_intel_md_fill_only(**_: int) -> int:
    return intel_figures()["fill_md"]


def mistake_intel_md_no_diagonal(**_: int) -> int:
    f = intel_figures()
    return f["nnz_md"] - f["poses"]


# --- code: symbolic_fill and min_degree_order -------------------------------------------------


def symbolic_fill(n: int, edges: Sequence[Sequence[int]], order: Sequence[int]) -> int:
    return so.fill_count(n, edges, order)


def min_degree_order(n: int, edges: Sequence[Sequence[int]]) -> list[int]:
    return so.min_degree_order(n, edges)


def _graph() -> Any:
    """Hypothesis strategy of ``(n, edges)``: 1–11 variables, any set of pairs (both directions,
    repeats allowed), biased towards pose-graph shapes (a chain plus a few extra pairs)."""
    from hypothesis import strategies as st

    def edges_for(n: int) -> Any:
        if n < 2:
            return st.just([])
        pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] != p[1])
        extra = st.lists(pair.map(list), max_size=2 * n)
        chain = st.booleans().map(lambda yes: [[i, i + 1] for i in range(n - 1)] if yes else [])
        return st.tuples(chain, extra).map(lambda parts: parts[0] + parts[1])

    return st.integers(1, 11).flatmap(lambda n: st.tuples(st.just(n), edges_for(n)))


def fill_inputs() -> Any:
    """``n``, ``edges`` from :func:`_graph`, and a random elimination order."""
    from hypothesis import strategies as st

    return _graph().flatmap(lambda g: st.fixed_dictionaries({
        "n": st.just(g[0]),
        "edges": st.just(g[1]),
        "order": st.permutations(list(range(g[0]))),
    }))


def min_degree_inputs() -> Any:
    from hypothesis import strategies as st

    return _graph().map(lambda g: {"n": g[0], "edges": g[1]})


def _adj(n: int, edges: Sequence[Sequence[int]]) -> list[set[int]]:
    return so.adjacency(n, edges)


def mistake_fill_all_pairs(n: int, edges: Sequence[Sequence[int]], order: Sequence[int]) -> int:
    """Every pair of remaining neighbours counted, even those already joined by an edge."""
    adj = _adj(n, edges)
    total = 0
    for v in order:
        nb = list(adj[v])
        total += len(nb) * (len(nb) - 1) // 2
        for a in nb:
            adj[a].update(u for u in nb if u != a)
            adj[a].discard(v)
        adj[v].clear()
    return total


def mistake_fill_no_propagation(n: int, edges: Sequence[Sequence[int]], order: Sequence[int]) -> int:
    """Fill counted, but never added to the graph: later eliminations do not see it."""
    adj = _adj(n, edges)
    done: set[int] = set()
    total = 0
    for v in order:
        nb = sorted(adj[v] - done)
        total += sum(1 for i, a in enumerate(nb) for b in nb[i + 1:] if b not in adj[a])
        done.add(v)
    return total


def mistake_fill_order_as_positions(n: int, edges: Sequence[Sequence[int]],
                                    order: Sequence[int]) -> int:
    """``order[v]`` read as the position of variable ``v`` (the inverse permutation)."""
    inverse = [0] * n
    for position, v in enumerate(order):
        inverse[v] = position
    return so.fill_count(n, edges, inverse)


def mistake_md_largest_tie(n: int, edges: Sequence[Sequence[int]]) -> list[int]:
    """Ties broken towards the largest index."""
    adj = _adj(n, edges)
    remaining = set(range(n))
    order: list[int] = []
    while remaining:
        v = min(remaining, key=lambda u: (len(adj[u]), -u))
        nb = list(adj[v])
        for a in nb:
            adj[a].update(u for u in nb if u != a)
            adj[a].discard(v)
        adj[v].clear()
        remaining.discard(v)
        order.append(v)
    return order


def mistake_md_static(n: int, edges: Sequence[Sequence[int]]) -> list[int]:
    """Sorted once by the original degree: the degrees are never updated."""
    adj = _adj(n, edges)
    return sorted(range(n), key=lambda u: (len(adj[u]), u))


def mistake_md_no_fill(n: int, edges: Sequence[Sequence[int]]) -> list[int]:
    """Eliminated variables removed, but their neighbours never joined: fill ignored."""
    adj = _adj(n, edges)
    remaining = set(range(n))
    order: list[int] = []
    while remaining:
        v = min(remaining, key=lambda u: (len(adj[u]), u))
        for a in adj[v]:
            adj[a].discard(v)
        adj[v].clear()
        remaining.discard(v)
        order.append(v)
    return order


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def graph_valid(n: int, edges: Sequence[Sequence[int]]) -> bool:
    """The graphs of ``min_degree_order`` and ``symbolic_fill``: 1–11 variables and pairs of two
    different variables (repeated or reversed pairs allowed)."""
    if not 1 <= n <= 11:
        return False
    for e in edges:
        if len(e) != 2:
            return False
        a, b = e
        if a == b or not (0 <= a < n and 0 <= b < n):
            return False
    return True


def fill_valid(n: int, edges: Sequence[Sequence[int]], order: Sequence[int]) -> bool:
    """``symbolic_fill``'s domain: a graph as above and ``order`` listing every variable once."""
    return graph_valid(n, edges) and sorted(order) == list(range(n))
