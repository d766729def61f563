import math


def edge_error(xi, xj, z):
    """Error of an edge that measured pose j from pose i: e = z^-1 (+) (xi^-1 (+) xj).

    xi, xj: poses (x, y, theta) in metres and radians (world frame).
    z: the measurement (dx, dy, dtheta): pose j as seen from pose i.
    Returns (ex, ey, etheta): zero when the poses agree with z; etheta wrapped into (-pi, pi].
    """
    raise NotImplementedError("express xj in xi's frame, then remove the measurement z")
