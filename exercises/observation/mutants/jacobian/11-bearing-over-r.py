# mistake: the bearing row divided by r instead of q = r²
import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    return [
        [-dx / r, -dy / r, 0.0, dx / r, dy / r],
        [dy / r, -dx / r, -1.0, -dy / r, dx / r],
    ]
