# mistake: atan(dy / dx) cannot tell a landmark in front from one behind
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    return math.sqrt(dx ** 2 + dy ** 2), math.atan(dy / dx) - thr
