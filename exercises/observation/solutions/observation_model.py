import math


def observation_model(xr, yr, thr, xj, yj):
    dx = xj - xr
    dy = yj - yr
    rng = math.sqrt(dx * dx + dy * dy)
    bearing = math.atan2(dy, dx) - thr
    return rng, bearing
