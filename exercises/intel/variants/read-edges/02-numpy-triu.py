# method: numpy: fill the upper triangle with triu_indices, then symmetrise
import numpy as np


def read_edges(text):
    rows = []
    iu = np.triu_indices(3)
    for line in text.splitlines():
        f = line.split()
        if len(f) == 12 and f[0] == "EDGE_SE2":
            vals = np.array(f[1:], dtype=float)
            om = np.zeros((3, 3))
            om[iu] = vals[5:]
            om = om + om.T - np.diag(np.diag(om))
            rows.append(np.concatenate([vals[:5], om.ravel()]))
    return np.array(rows).reshape(-1, 14)
