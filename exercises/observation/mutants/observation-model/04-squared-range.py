# mistake: returns the squared distance (m^2) as the range
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    return dx * dx + dy * dy, math.atan2(dy, dx) - thr
