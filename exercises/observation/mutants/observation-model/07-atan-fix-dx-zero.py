# mistake: atan(dy/dx) with the quadrant fixed for dx < 0, but dx == 0 divides by zero
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    world = math.atan(dy / dx)
    if dx < 0:
        world += math.pi
    return math.hypot(dx, dy), world - thr
