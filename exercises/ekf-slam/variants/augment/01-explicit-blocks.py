# method: the blocks written out entry by entry with numpy, Jacobians by hand
import math

import numpy as np


def augment(mu, P, z, R):
    P, R = np.asarray(P, dtype=float), np.asarray(R, dtype=float)
    r, phi = z
    a = mu[2] + phi
    c, s = math.cos(a), math.sin(a)
    Gr = np.array([[1.0, 0.0, -r * s], [0.0, 1.0, r * c]])
    Gz = np.array([[c, -r * s], [s, r * c]])
    cross = Gr @ P[:3, :]
    block = Gr @ P[:3, :3] @ Gr.T + Gz @ R @ Gz.T
    return np.block([[P, cross.T], [cross, block]])
