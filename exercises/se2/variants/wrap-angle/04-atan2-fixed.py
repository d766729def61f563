# method: atan2(sin, cos) with numpy, then the one value it gets wrong moved to pi
import numpy as np


def wrap_angle(a):
    r = float(np.arctan2(np.sin(a), np.cos(a)))
    if r <= -np.pi:
        r = float(np.pi)
    return r
