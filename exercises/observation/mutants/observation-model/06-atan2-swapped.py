# mistake: atan2(dx, dy) with the arguments swapped
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    return math.hypot(dx, dy), math.atan2(dx, dy) - thr
