# mistake: the offset robot minus landmark, so the bearing points away from the landmark
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xr - xj, yr - yj
    return math.hypot(dx, dy), math.atan2(dy, dx) - thr
