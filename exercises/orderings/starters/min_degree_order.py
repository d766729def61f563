def min_degree_order(n, edges):
    """Greedy minimum-degree elimination order.

    n:     number of variables, 0 ... n-1 (n >= 1).
    edges: list of pairs [i, j], i != j (a pair may repeat or appear reversed).

    Returns a list of the n variables: each step eliminates the remaining variable with the
    fewest remaining neighbours (ties: the smallest index) and joins its neighbours.
    """
    raise NotImplementedError("TODO: pick, join the neighbours, remove; n times")
