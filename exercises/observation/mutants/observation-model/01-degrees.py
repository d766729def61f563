# mistake: returns the bearing in degrees
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    return math.hypot(dx, dy), math.degrees(math.atan2(dy, dx) - thr)
