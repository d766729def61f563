# mistake: the range row divided by q instead of sqrt(q)
def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    return [
        [-dx / q, -dy / q, 0.0, dx / q, dy / q],
        [dy / q, -dx / q, -1.0, -dy / q, dx / q],
    ]
