# method: numpy boolean adjacency matrix; degrees are masked row sums, argmin picks the smallest index on ties
import numpy as np


def min_degree_order(n, edges):
    a = np.zeros((n, n), dtype=bool)
    for i, j in edges:
        a[i, j] = a[j, i] = True
    alive = np.ones(n, dtype=bool)
    order = []
    for _ in range(n):
        degree = np.where(alive, (a & alive).sum(axis=1), n + 1)
        v = int(np.argmin(degree))
        nb = a[v] & alive
        nb[v] = False
        a |= np.outer(nb, nb)
        np.fill_diagonal(a, False)
        alive[v] = False
        order.append(v)
    return order
