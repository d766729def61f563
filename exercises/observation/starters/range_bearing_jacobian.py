import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    """Jacobian of h = [range, bearing] with respect to (xr, yr, thr, xj, yj).

    xr, yr: robot position (m)          thr: robot heading (rad)
    xj, yj: landmark position (m)       always more than 0.5 m from the robot

    Returns a 2 x 5 array (nested lists, tuples or a numpy array):
        row 0: d range   / d(xr, yr, thr, xj, yj)
        row 1: d bearing / d(xr, yr, thr, xj, yj)
    """
    raise NotImplementedError("differentiate range = sqrt(q) and bearing = atan2(dy, dx) - thr")
