import numpy as np


def build_omega(n, edges):
    """Information matrix of a 1-D pose graph.

    n:     number of poses x_0 … x_{n-1} (int, at least 1).
    edges: list of (i, j, omega) with 0 <= i, j < n, i != j, and omega > 0 the information of
           the constraint between poses i and j (1/m²). Pairs may repeat.

    Returns Ω, shape (n, n): +omega at (i, i) and (j, j), −omega at (i, j) and (j, i), summed
    over all edges.
    """
    raise NotImplementedError("TODO: build and return the n×n information matrix")
