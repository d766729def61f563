# mistake: grows P with np.pad(np.array(P)), an integer array when P's entries are whole numbers, so the new blocks are truncated
import math

import numpy as np


def augment(mu, P, z, R):
    n = len(P)
    out = np.pad(np.array(P), ((0, 2), (0, 2)))
    Pf, Rf = np.array(P, dtype=float), np.array(R, dtype=float)
    r, a = z[0], mu[2] + z[1]
    c, s = math.cos(a), math.sin(a)
    Gr = np.array([[1.0, 0.0, -r * s], [0.0, 1.0, r * c]])
    Gz = np.array([[c, -r * s], [s, r * c]])
    cross = Gr @ Pf[:3, :]
    out[n:, :n] = cross
    out[:n, n:] = cross.T
    out[n:, n:] = Gr @ Pf[:3, :3] @ Gr.T + Gz @ Rf @ Gz.T
    return out
