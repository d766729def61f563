# method: a numpy boolean adjacency matrix; fill = new True entries of the outer product of the neighbour mask
import numpy as np


def symbolic_fill(n, edges, order):
    a = np.zeros((n, n), dtype=bool)
    for i, j in edges:
        a[i, j] = a[j, i] = True
    alive = np.ones(n, dtype=bool)
    fill = 0
    for v in order:
        nb = a[v] & alive
        nb[v] = False
        clique = np.outer(nb, nb)
        np.fill_diagonal(clique, False)
        new = clique & ~a
        fill += int(new.sum()) // 2
        a |= clique
        alive[v] = False
    return fill
