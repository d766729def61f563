# mistake: only the pose block (2 x 3): the landmark columns left out
import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    return [[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, -1.0]]
