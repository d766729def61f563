# method: a numpy copy of the grid, the beam's cells by exact Fractions, fancy indexing by rows then columns
import math
from fractions import Fraction

import numpy as np


def update_beam(grid, x0, y0, x1, y1, l_occ, l_free):
    out = np.array(grid, dtype=float)
    n = max(abs(x1 - x0), abs(y1 - y0))
    half = Fraction(1, 2)
    xs = [x0 + math.floor(Fraction(k * (x1 - x0), n) + half) if n else x0 for k in range(n + 1)]
    ys = [y0 + math.floor(Fraction(k * (y1 - y0), n) + half) if n else y0 for k in range(n + 1)]
    out[ys[:-1], xs[:-1]] += l_free
    out[ys[-1], xs[-1]] += l_occ
    return out.tolist()
