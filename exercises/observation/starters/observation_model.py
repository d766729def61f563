import math


def observation_model(xr, yr, thr, xj, yj):
    """Predicted range-bearing measurement of landmark (xj, yj) from pose (xr, yr, thr).

    xr, yr: robot position (m)          thr: robot heading (rad, counter-clockwise from world x)
    xj, yj: landmark position (m)       never equal to the robot position

    Returns (range, bearing): range in metres, bearing in radians measured from the robot's
    heading, positive to its left. Wrapping the bearing into (-pi, pi] is optional.
    """
    raise NotImplementedError("compute the offset dx, dy, then the range and the bearing")
