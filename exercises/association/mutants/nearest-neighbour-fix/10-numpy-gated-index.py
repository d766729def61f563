# mistake: numpy argmin over the candidates inside the gate only, so the index counts gated ones
import numpy as np


def nearest_neighbour(z, landmarks, s00, s11, gate):
    h = np.array(landmarks, dtype=float).reshape(-1, 2)
    nu = np.asarray(z, dtype=float) - h
    d2 = nu[:, 0] ** 2 / s00 + nu[:, 1] ** 2 / s11
    inside = d2[d2 < gate]
    if inside.size == 0:
        return -1
    return int(np.argmin(inside))
