import math


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    """Jacobian of h = [range, bearing] with respect to (xr, yr, thr, xj, yj).

    xr, yr: robot position (m), -200 to 200     thr: robot heading (rad), -10 to 10
    xj, yj: landmark position (m), -200 to 200, at least 0.5 m from the robot

    Returns a 2 x 5 array (nested lists, tuples or a numpy array):
        row 0: d range   / d(xr, yr, thr, xj, yj)
        row 1: d bearing / d(xr, yr, thr, xj, yj)
    """
    raise NotImplementedError("differentiate range = sqrt(q) and bearing = atan2(dy, dx) - thr")
