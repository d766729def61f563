# mistake: the world-frame direction, the robot's heading not subtracted
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    return math.hypot(dx, dy), math.atan2(dy, dx)
