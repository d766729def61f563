# method: analytic, plain Python, math.hypot for the range; a tuple of tuples
import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    q = r * r
    return (
        (-dx / r, -dy / r, 0, dx / r, dy / r),
        (dy / q, -dx / q, -1, -dy / q, dx / q),
    )
