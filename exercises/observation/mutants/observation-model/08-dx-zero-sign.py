# mistake: the dx == 0 case returns +pi/2 whatever the sign of dy
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    if dx == 0:
        world = math.pi / 2
    else:
        world = math.atan(dy / dx)
        if dx < 0:
            world += math.pi
    return math.hypot(dx, dy), world - thr
