# mistake: d bearing / d theta = +1
import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    return [
        [-dx / r, -dy / r, 0.0, dx / r, dy / r],
        [dy / q, -dx / q, 1.0, -dy / q, dx / q],
    ]
