# mistake: tests `if not landmarks` for an empty map, which raises for a numpy array of candidates
import numpy as np


def nearest_neighbour(z, landmarks, s00, s11, gate):
    if not landmarks:
        return -1
    d2 = [(z[0] - h[0]) ** 2 / s00 + (z[1] - h[1]) ** 2 / s11 for h in landmarks]
    j = int(np.argmin(d2))
    return j if d2[j] < gate else -1
