# method: np.piecewise on the two sides of the boundary, DCS as g2o writes it (scale, then square)
import numpy as np


def robust_weights(kind, s, k):
    s = np.array(s, dtype=float)
    if s.size == 0:
        return np.zeros(0)
    phi = k**2
    if kind == "huber":
        return np.piecewise(s, [s <= phi, s > phi], [1.0, lambda v: k / np.sqrt(v)])
    if kind == "dcs":
        scale = np.piecewise(s, [s <= phi, s > phi], [1.0, lambda v: 2 * phi / (phi + v)])
        return scale * scale
    if kind == "cauchy":
        return phi / (phi + s)
    return np.full(s.shape, 1.0)
