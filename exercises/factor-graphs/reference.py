"""Reference code for chapter ``factor-graphs``: counting a factor graph, and fill-in.

Variables are the unknowns (poses, landmarks); factors are the measurements and priors linking
them. Eliminating a variable during sparse factorisation links all of its remaining neighbours
to each other: every such link that was not already there is a *fill-in* edge.

Every exercise function takes the exercise's parameters (or a code exercise's arguments) as
keyword arguments. Functions whose name starts with ``mistake_`` are wrong implementations or
wrong answers of a named misconception.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations
from typing import Any

Pair = Sequence[int]


def _adjacency(n: int, edges: Sequence[Pair]) -> list[set[int]]:
    adj: list[set[int]] = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    return adj


def fill_in(n: int, edges: Sequence[Pair], order: Sequence[int]) -> int:
    """Number of new edges created by eliminating the nodes ``0 … n−1`` in ``order``.

    Eliminating ``v`` connects every pair of its remaining neighbours (counting the pairs not
    yet connected) and then removes ``v`` from the graph.
    """
    adj = _adjacency(n, edges)
    created = 0
    for v in order:
        for a, b in combinations(sorted(adj[v]), 2):
            if b not in adj[a]:
                adj[a].add(b)
                adj[b].add(a)
                created += 1
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return created


def fill_in_inputs() -> Any:
    """Hypothesis strategy for ``fill_in``: 1–20 nodes, up to 40 distinct undirected edges (each
    a list ``[a, b]`` in either orientation, no self-loops) plus up to 3 repeats of them (two
    factors between the same pair of variables, possibly reversed), in any order, and an
    elimination order (a permutation of the nodes, as a list)."""
    from hypothesis import strategies as st

    @st.composite
    def inputs(draw: Any) -> dict[str, Any]:
        n = draw(st.integers(1, 20))
        pairs = [(a, b) for a in range(n) for b in range(a + 1, n)]
        chosen: list[tuple[int, int]] = []
        if pairs:
            chosen = draw(st.lists(st.sampled_from(pairs), unique=True,
                                   max_size=min(len(pairs), 40)))
        if chosen:
            chosen += draw(st.lists(st.sampled_from(chosen), max_size=3))
        edges = [[a, b] if draw(st.booleans()) else [b, a] for a, b in chosen]
        return {"n": n, "edges": draw(st.permutations(edges)),
                "order": draw(st.permutations(list(range(n))))}

    return inputs()


def mistake_fill_in_all_pairs(n: int, edges: Sequence[Pair], order: Sequence[int]) -> int:
    """Counts every pair of remaining neighbours, including pairs already joined by an edge."""
    adj = _adjacency(n, edges)
    counted = 0
    for v in order:
        for a, b in combinations(sorted(adj[v]), 2):
            counted += 1
            adj[a].add(b)
            adj[b].add(a)
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return counted


def mistake_fill_in_kept_eliminated(n: int, edges: Sequence[Pair], order: Sequence[int]) -> int:
    """Never removes eliminated nodes, so they keep being treated as neighbours."""
    adj = _adjacency(n, edges)
    created = 0
    for v in order:
        for a, b in combinations(sorted(adj[v]), 2):
            if b not in adj[a]:
                adj[a].add(b)
                adj[b].add(a)
                created += 1
    return created


def mistake_fill_in_not_added(n: int, edges: Sequence[Pair], order: Sequence[int]) -> int:
    """Counts the missing pairs but never adds them to the graph, so later eliminations do not
    see the fill-in edges."""
    adj = _adjacency(n, edges)
    created = 0
    for v in order:
        created += sum(b not in adj[a] for a, b in combinations(sorted(adj[v]), 2))
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return created


# --- counting factors and variables ---------------------------------------------------------


def factor_graph_counts(num_poses: int, num_landmarks: int, sightings: int) -> list[int]:
    """``[factors, variables]``: one prior, ``num_poses − 1`` odometry factors and
    ``num_landmarks · sightings`` observation factors; one variable per pose and landmark."""
    factors = 1 + (num_poses - 1) + num_landmarks * sightings
    return [factors, num_poses + num_landmarks]


def mistake_counts_no_prior(num_poses: int, num_landmarks: int, sightings: int) -> list[int]:
    """The prior on the first pose left out of the factors."""
    factors, variables = factor_graph_counts(num_poses, num_landmarks, sightings)
    return [factors - 1, variables]


def mistake_counts_one_observation_each(num_poses: int, num_landmarks: int,
                                        sightings: int) -> list[int]:
    """One observation factor per landmark instead of one per sighting."""
    return [1 + (num_poses - 1) + num_landmarks, num_poses + num_landmarks]


def mistake_counts_poses_only(num_poses: int, num_landmarks: int, sightings: int) -> list[int]:
    """Only the poses counted as variables."""
    factors, _ = factor_graph_counts(num_poses, num_landmarks, sightings)
    return [factors, num_poses]


def constraint_dof(num_poses: int, num_landmarks: int, num_observations: int,
                   pose_dof: int, landmark_dof: int) -> int:
    """Scalar equations contributed by all factors: odometry and the prior constrain a full
    pose (``pose_dof`` each), an observation ``landmark_dof`` numbers."""
    odometry = num_poses - 1
    return (odometry + 1) * pose_dof + num_observations * landmark_dof


def mistake_dof_no_prior(num_poses: int, num_landmarks: int, num_observations: int,
                         pose_dof: int, landmark_dof: int) -> int:
    """The prior's equations left out."""
    return constraint_dof(num_poses, num_landmarks, num_observations, pose_dof, landmark_dof) \
        - pose_dof


def mistake_dof_unknowns(num_poses: int, num_landmarks: int, num_observations: int,
                         pose_dof: int, landmark_dof: int) -> int:
    """The number of unknowns (variables' degrees of freedom) instead of constraints."""
    return num_poses * pose_dof + num_landmarks * landmark_dof


def mistake_dof_factor_count(num_poses: int, num_landmarks: int, num_observations: int,
                             pose_dof: int, landmark_dof: int) -> int:
    """The number of factors, each counted as one constraint."""
    return num_poses + num_observations


def star_fill_in(leaves: int) -> int:
    """Fill-in of eliminating the centre of a star with ``leaves`` leaves first: k(k−1)/2."""
    return fill_in(leaves + 1, [(0, k) for k in range(1, leaves + 1)], list(range(leaves + 1)))


def mistake_star_ordered_pairs(leaves: int) -> int:
    """``k(k−1)``: every pair counted twice, once in each direction."""
    return leaves * (leaves - 1)


def mistake_star_squared(leaves: int) -> int:
    """``k²``: pairs of a leaf with itself counted too."""
    return leaves * leaves


def mistake_star_leaves(leaves: int) -> int:
    """``k``: one new edge per leaf."""
    return leaves


# --- elimination on a chain (these call the course library ``slamcourse.slam.factor``) ----

from slamcourse.slam import factor as _factor  # noqa: E402


def chain_fill_edge(num_poses: int, eliminated: int) -> list[int]:
    """The fill-in edge ``[a, b]`` (a < b) created by eliminating pose ``eliminated`` first from
    the chain ``x0 — … — x(num_poses−1)``."""
    order = [eliminated] + [k for k in range(num_poses) if k != eliminated]
    (edge, *_rest) = _factor.eliminate(num_poses, _factor.chain(num_poses), order)
    return list(edge)


def mistake_chain_edge_ends(num_poses: int, eliminated: int) -> list[int]:
    """The two ends of the chain linked, as if elimination closed a loop."""
    return [0, num_poses - 1]


def mistake_chain_edge_kept_node(num_poses: int, eliminated: int) -> list[int]:
    """An edge that still touches the eliminated node (``[k − 1, k]``), which already existed."""
    return [eliminated - 1, eliminated]


def middle_out_fill(num_poses: int, start: int) -> int:
    """Fill-in of eliminating a chain from pose ``start`` outwards to the end
    (``start, start+1, …, n−1``), then ``start−1`` down to ``0``."""
    order = list(range(start, num_poses)) + list(range(start - 1, -1, -1))
    return _factor.fill_in(num_poses, _factor.chain(num_poses), order)


def mistake_middle_out_none(num_poses: int, start: int) -> int:
    """"A chain never fills in": true only when eliminated from an end."""
    return 0


def mistake_middle_out_first_only(num_poses: int, start: int) -> int:
    """Only the first elimination counted as creating an edge."""
    return 1


def constraint_surplus(num_poses: int, num_landmarks: int, num_observations: int,
                       pose_dof: int, landmark_dof: int) -> int:
    """Scalar constraints minus scalar unknowns."""
    return (_factor.constraint_dof(num_poses, num_observations, pose_dof, landmark_dof)
            - _factor.unknown_dof(num_poses, num_landmarks, pose_dof, landmark_dof))


def mistake_surplus_variables(num_poses: int, num_landmarks: int, num_observations: int,
                              pose_dof: int, landmark_dof: int) -> int:
    """Constraints minus the number of variables (not their degrees of freedom)."""
    return (_factor.constraint_dof(num_poses, num_observations, pose_dof, landmark_dof)
            - (num_poses + num_landmarks))


def mistake_surplus_factors(num_poses: int, num_landmarks: int, num_observations: int,
                            pose_dof: int, landmark_dof: int) -> int:
    """Factors minus variables, each counted once."""
    return (num_poses + num_observations) - (num_poses + num_landmarks)


# --- the domain the prompt states (``valid:`` of fill_in) -------------------------------------


def fill_in_valid(n: int, edges: Sequence[Pair], order: Sequence[int]) -> bool:
    """``fill_in``'s domain: 1–20 nodes, pairs of two different nodes (repeats allowed, in
    either order) with at most 40 different edges, and ``order`` a permutation of the nodes."""
    if not 1 <= n <= 20:
        return False
    distinct = set()
    for e in edges:
        if len(e) != 2:
            return False
        a, b = e
        if a == b or not (0 <= a < n and 0 <= b < n):
            return False
        distinct.add((min(a, b), max(a, b)))
    return len(distinct) <= 40 and sorted(order) == list(range(n))
