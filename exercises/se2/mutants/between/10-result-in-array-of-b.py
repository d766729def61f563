# mistake: builds the result in np.array(b), an integer array when b's numbers are whole, so the offset and the heading change are truncated
import math

import numpy as np


def between(a, b):
    out = np.array(b)
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    out[0] = c * dx + s * dy
    out[1] = -s * dx + c * dy
    out[2] = b[2] - a[2]
    return out
