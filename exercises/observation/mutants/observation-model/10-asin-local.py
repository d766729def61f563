# mistake: bearing = asin(local y / range), which folds landmarks behind the robot to the front
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    local_y = -math.sin(thr) * dx + math.cos(thr) * dy
    return r, math.asin(max(-1.0, min(1.0, local_y / r)))
