# mistake: subtracts xi from np.asarray(xj, dtype=float) in place, which is the caller's own xj when it is a float array
import math

import numpy as np


def edge_error(xi, xj, z):
    d = np.asarray(xj, dtype=float)
    d -= np.asarray(xi, dtype=float)
    c, s = math.cos(xi[2]), math.sin(xi[2])
    x, y = c * d[0] + s * d[1] - z[0], -s * d[0] + c * d[1] - z[1]
    cz, sz = math.cos(z[2]), math.sin(z[2])
    return cz * x + sz * y, -sz * x + cz * y, math.remainder(d[2] - z[2], 2 * math.pi)
