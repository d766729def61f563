import math


def observation_model(xr, yr, thr, xj, yj):
    """Predicted range-bearing measurement of landmark (xj, yj) from pose (xr, yr, thr).

    xr, yr: robot position (m), -200 to 200
    thr:    robot heading (rad, counter-clockwise from world x), -10 to 10, not always wrapped
    xj, yj: landmark position (m), -200 to 200, at least 0.1 m from the robot

    Returns (range, bearing): range in metres, bearing in radians measured from the robot's
    heading, positive to its left. Wrapping the bearing into (-pi, pi] is optional.
    """
    raise NotImplementedError("compute the offset dx, dy, then the range and the bearing")
