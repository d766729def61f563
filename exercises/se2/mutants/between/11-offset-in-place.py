# mistake: subtracts a's position from np.asarray(b, dtype=float) in place, which is the caller's own b when b is a float array
import math

import numpy as np


def between(a, b):
    d = np.asarray(b, dtype=float)
    d[:2] -= np.asarray(a, dtype=float)[:2]
    c, s = math.cos(a[2]), math.sin(a[2])
    return [c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2] - a[2]]
