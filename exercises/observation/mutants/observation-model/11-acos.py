# mistake: world direction from acos(dx / r), which loses the sign of dy
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    return r, math.acos(dx / r) - thr
