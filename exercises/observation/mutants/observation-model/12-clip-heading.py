# mistake: clamps the heading into [-pi, pi] "to normalise it" instead of wrapping it
import math


def observation_model(xr, yr, thr, xj, yj):
    thr = max(-math.pi, min(math.pi, thr))
    dx, dy = xj - xr, yj - yr
    return math.hypot(dx, dy), math.atan2(dy, dx) - thr
