# mistake: the bearing row first, the range row second
import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    return [
        [dy / q, -dx / q, -1.0, -dy / q, dx / q],
        [-dx / r, -dy / r, 0.0, dx / r, dy / r],
    ]
