"""Variable orderings and fill-in of sparse Cholesky factors: the mathematics of chapter 17.

A least-squares problem's information matrix ``H`` has a nonzero block ``(i, j)`` exactly when
variables ``i`` and ``j`` share a factor. Its sparsity pattern is an undirected graph on the
variables ``0 … n−1`` (edges are unordered pairs ``(i, j)``, ``i ≠ j``; duplicates and self-loops
carry no extra structure and are ignored). Factoring ``H = L Lᵀ`` eliminates the variables one by
one in some order; eliminating ``v`` joins all of ``v``'s not-yet-eliminated neighbours into a
clique. The pairs it joins that were not already edges are *fill*: new nonzeros of ``L`` that
``H`` did not have. The number of nonzeros of ``L`` (one per variable on the diagonal plus one
per edge of the filled graph below it) decides the memory and time of the solve.

Everything here is symbolic (counts of structural nonzeros) and uses the standard library only;
the tests check the counts against scipy's numerical LU.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

Edge = tuple[int, int]


def adjacency(n: int, edges: Iterable[Sequence[int]]) -> list[set[int]]:
    """Neighbour sets of the graph on ``0 … n−1`` (self-loops and duplicates dropped)."""
    adj: list[set[int]] = [set() for _ in range(n)]
    for edge in edges:
        i, j = int(edge[0]), int(edge[1])
        if i != j:
            adj[i].add(j)
            adj[j].add(i)
    return adj


def unique_edges(edges: Iterable[Sequence[int]]) -> set[Edge]:
    """The distinct unordered pairs ``(min, max)`` of ``edges``, self-loops dropped."""
    return {(min(int(e[0]), int(e[1])), max(int(e[0]), int(e[1]))) for e in edges if e[0] != e[1]}


def fill_edges(n: int, edges: Iterable[Sequence[int]], order: Sequence[int]) -> set[Edge]:
    """The fill created by eliminating the variables in ``order`` (a permutation of ``0 … n−1``).

    Returns the set of new pairs ``(min, max)``: those joined by an elimination that were not
    edges of the original graph (nor joined by an earlier elimination).
    """
    adj = adjacency(n, edges)
    fill: set[Edge] = set()
    for v in order:
        neighbours = sorted(adj[v])
        for a_index, a in enumerate(neighbours):
            for b in neighbours[a_index + 1 :]:
                if b not in adj[a]:
                    adj[a].add(b)
                    adj[b].add(a)
                    fill.add((a, b))
        for u in neighbours:
            adj[u].discard(v)
        adj[v].clear()
    return fill


def fill_count(n: int, edges: Iterable[Sequence[int]], order: Sequence[int]) -> int:
    """Number of fill edges of the elimination ``order`` (see :func:`fill_edges`)."""
    return len(fill_edges(n, edges, order))


def factor_nonzeros(n: int, edges: Iterable[Sequence[int]], order: Sequence[int]) -> int:
    """Structural nonzeros of the lower-triangular factor ``L``, diagonal included.

    ``n`` diagonal entries, plus one entry per distinct original edge, plus one per fill edge.
    """
    edge_list = [tuple(e) for e in edges]
    return n + len(unique_edges(edge_list)) + fill_count(n, edge_list, order)


def column_counts(n: int, edges: Iterable[Sequence[int]], order: Sequence[int]) -> list[int]:
    """Off-diagonal nonzeros of each column of ``L``, in elimination order.

    Column ``k`` of ``L`` has one entry per neighbour the ``k``-th eliminated variable still has
    when it is eliminated. Factoring costs about ``Σ c_k²`` multiply-adds.
    """
    adj = adjacency(n, edges)
    counts: list[int] = []
    for v in order:
        neighbours = list(adj[v])
        counts.append(len(neighbours))
        for a in neighbours:
            adj[a].update(u for u in neighbours if u != a)
            adj[a].discard(v)
        adj[v].clear()
    return counts


def min_degree_order(n: int, edges: Iterable[Sequence[int]]) -> list[int]:
    """Greedy minimum-degree elimination order of the graph on ``0 … n−1``.

    At each step, eliminate the remaining variable with the fewest remaining neighbours (ties: the
    smallest index), then join its neighbours into a clique. Exact, O(n²) per step at worst:
    the approximate-minimum-degree (AMD) codes of real solvers estimate the degrees instead.
    """
    adj = adjacency(n, edges)
    remaining = set(range(n))
    order: list[int] = []
    while remaining:
        v = min(remaining, key=lambda u: (len(adj[u]), u))
        neighbours = list(adj[v])
        for a in neighbours:
            adj[a].update(u for u in neighbours if u != a)
            adj[a].discard(v)
        adj[v].clear()
        remaining.discard(v)
        order.append(v)
    return order


def g2o_pose_edges(text: str) -> tuple[int, list[Edge]]:
    """Number of ``VERTEX_SE2`` poses and the ``(i, j)`` of each ``EDGE_SE2`` of a g2o file."""
    poses = 0
    edges: list[Edge] = []
    for line in text.splitlines():
        fields = line.split()
        if fields and fields[0] == "VERTEX_SE2":
            poses += 1
        elif fields and fields[0] == "EDGE_SE2":
            edges.append((int(fields[1]), int(fields[2])))
    return poses, edges


# --- synthetic graphs ---------------------------------------------------------------------------


def chain(n: int) -> list[Edge]:
    """Odometry chain ``0 − 1 − … − (n−1)``."""
    return [(i, i + 1) for i in range(n - 1)]


def star(leaves: int) -> list[Edge]:
    """Hub ``0`` joined to each of the leaves ``1 … leaves``."""
    return [(0, k) for k in range(1, leaves + 1)]


def grid(rows: int, cols: int) -> list[Edge]:
    """4-neighbour grid, variable ``r·cols + c`` at row ``r``, column ``c``."""
    edges: list[Edge] = []
    for r in range(rows):
        for c in range(cols):
            v = r * cols + c
            if c + 1 < cols:
                edges.append((v, v + 1))
            if r + 1 < rows:
                edges.append((v, v + cols))
    return edges
