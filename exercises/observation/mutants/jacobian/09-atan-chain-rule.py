# mistake: differentiates atan(dy/dx) by the chain rule, dividing by dx (fails when dx = 0)
import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    s = 1.0 / (1.0 + (dy / dx) ** 2)  # d atan(u)/du with u = dy/dx
    dphi_dxj = s * (-dy / dx ** 2)
    dphi_dyj = s * (1.0 / dx)
    return [
        [-dx / r, -dy / r, 0.0, dx / r, dy / r],
        [-dphi_dxj, -dphi_dyj, -1.0, dphi_dxj, dphi_dyj],
    ]
