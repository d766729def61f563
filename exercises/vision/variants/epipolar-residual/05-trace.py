# method: trace(x x'^T E), the same scalar written as a trace (numpy)
import numpy as np


def epipolar_residual(E, x, x2):
    return float(np.trace(np.outer(x, x2) @ np.asarray(E, dtype=float)))
