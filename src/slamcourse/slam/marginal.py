"""Marginalisation in information form: Schur complements, marginal covariances, fill-in.

A Gaussian over variables ``x`` in information (canonical) form is ``H`` (symmetric positive
definite, n×n) and ``b`` (n): ``p(x) ∝ exp(−½ xᵀHx + bᵀx)``, mean ``H⁻¹b``, covariance ``H⁻¹``.
(The Gauss-Newton system ``H Δ = −b`` of the pose-graph chapter is the same object with ``−b``.)

- **Marginalising** the variables ``m`` out and keeping ``a`` is the Schur complement
  ``H' = H_aa − H_am H_mm⁻¹ H_ma``, ``b' = b_a − H_am H_mm⁻¹ b_m``. In covariance form it is
  only dropping the rows and columns of ``m``.
- **Conditioning** on ``m`` is the reverse: dropping rows and columns in information form
  (``H_aa``), a Schur complement in covariance form.
- The marginal covariance of a block is a block of ``H⁻¹``: found from a Cholesky factor by
  solving for the block's columns only, never as ``(H_aa)⁻¹`` (that is the conditional).

Indices are 0-based scalar indices into ``H`` unless a function says "variables" (blocks).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

Matrix = NDArray[np.float64]
Vector = NDArray[np.float64]
Pair = tuple[int, int]


def _split(n: int, keep: Sequence[int]) -> tuple[list[int], list[int]]:
    kept = [int(k) for k in keep]
    gone = [i for i in range(n) if i not in set(kept)]
    return kept, gone


def schur_complement(h: ArrayLike, b: ArrayLike, keep: Sequence[int]) -> tuple[Matrix, Vector]:
    """Marginalise every variable not in ``keep`` out of ``(H, b)``.

    Returns ``(H', b')`` with rows (and columns) in the order of ``keep``:
    ``H' = H_aa − H_am H_mm⁻¹ H_ma``, ``b' = b_a − H_am H_mm⁻¹ b_m``.
    ``H_mm`` must be positive definite (it is when ``H`` is).
    """
    hh = np.array(h, dtype=float)
    bb = np.array(b, dtype=float).reshape(-1)
    a, m = _split(len(hh), keep)
    h_aa, h_am, h_mm = hh[np.ix_(a, a)], hh[np.ix_(a, m)], hh[np.ix_(m, m)]
    if not m:
        return h_aa, bb[a]
    from scipy.linalg import cho_factor, cho_solve  # type: ignore[import-untyped]

    factor = cho_factor(h_mm)
    x = cho_solve(factor, np.column_stack([h_am.T, bb[m]]))  # H_mm⁻¹ [H_ma | b_m]
    h_new = h_aa - h_am @ x[:, :-1]
    return (h_new + h_new.T) / 2, bb[a] - h_am @ x[:, -1]


def marginal_covariance(h: ArrayLike, block: Sequence[int]) -> Matrix:
    """The block ``(H⁻¹)[block, block]`` (rows and columns in ``block``'s order) without
    forming ``H⁻¹``: one Cholesky factorisation, then a solve for ``block``'s unit columns."""
    from scipy.linalg import cho_factor, cho_solve

    hh = np.array(h, dtype=float)
    idx = [int(k) for k in block]
    units = np.zeros((len(hh), len(idx)))
    units[idx, range(len(idx))] = 1.0
    columns = cho_solve(cho_factor(hh, lower=True), units)  # the columns of H⁻¹ we need
    sigma = columns[idx, :]
    return np.asarray((sigma + sigma.T) / 2, dtype=float)


def conditional_covariance(h: ArrayLike, block: Sequence[int]) -> Matrix:
    """``(H_block,block)⁻¹``: the covariance of ``block`` *given* every other variable."""
    hh = np.array(h, dtype=float)
    idx = [int(k) for k in block]
    return np.asarray(np.linalg.inv(hh[np.ix_(idx, idx)]), dtype=float)


def blocks(variables: Iterable[int], size: int = 3) -> list[int]:
    """Scalar indices of whole variables of ``size`` numbers each (``[1, 0]`` → ``3 4 5 0 1 2``)."""
    return [size * int(v) + k for v in variables for k in range(size)]


def neighbours(n: int, edges: Iterable[Sequence[int]]) -> list[set[int]]:
    """Adjacency sets of the variables ``0 … n−1`` (pairs may repeat or come reversed)."""
    adj: list[set[int]] = [set() for _ in range(n)]
    for e in edges:
        i, j = int(e[0]), int(e[1])
        if i != j:
            adj[i].add(j)
            adj[j].add(i)
    return adj


def marginal_fill(n: int, edges: Iterable[Sequence[int]], removed: Iterable[int]) -> list[Pair]:
    """The pairs ``(i, j)``, ``i < j``, of variables that are linked after marginalising
    ``removed`` (one at a time; the order does not change the result) and were not linked
    before: the fill-in. Only pairs of kept variables are listed, sorted."""
    adj = neighbours(n, edges)
    before = {(i, j) for i in range(n) for j in adj[i] if i < j}
    for v in removed:
        live = sorted(adj[v])
        for i in live:
            adj[i].discard(v)
            adj[i].update(u for u in live if u != i)
        adj[v] = set()
    gone = set(int(v) for v in removed)
    after = {(i, j) for i in range(n) for j in adj[i] if i < j and i not in gone and j not in gone}
    return sorted(after - before)


def markov_blanket(n: int, edges: ArrayLike, removed: Iterable[int]) -> list[int]:
    """The kept variables linked to any of ``removed`` (directly or through other removed
    ones): the variables the prior left by marginalising ``removed`` is on. Every removed
    variable goes, so these are the kept variables with an edge to one of them (a chain
    through removed variables ends on an edge from the last of them). ``edges``: pairs, or
    an m×2 integer array (a bundle adjustment's hundreds of thousands of edges)."""
    gone = np.zeros(n, dtype=bool)
    gone[[int(v) for v in removed]] = True
    i, j = np.asarray(edges, dtype=np.int64).reshape(-1, 2).T
    linked = np.concatenate([j[gone[i] & ~gone[j]], i[gone[j] & ~gone[i]]])
    return [int(v) for v in np.unique(linked)]
