# method: atan(dy/dx) with every quadrant and dx == 0 handled; bearing wrapped into [0, 2π)
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    if dx > 0:
        world = math.atan(dy / dx)
    elif dx < 0:
        world = math.atan(dy / dx) + math.pi
    else:
        world = math.copysign(math.pi / 2, dy)
    bearing = (world - thr) % (2 * math.pi)
    return [math.sqrt(dx * dx + dy * dy), bearing]
