# mistake: atan2(sin a, cos a) with -pi moved to pi: sin and cos lose the last bits, so an angle a hair above pi comes back as pi instead of a hair above -pi
import numpy as np


def wrap_angle(a):
    r = float(np.arctan2(np.sin(a), np.cos(a)))
    if r <= -np.pi:
        r = float(np.pi)
    return r
