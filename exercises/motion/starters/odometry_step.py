import math


def odometry_step(pose, u):
    """The pose after the odometry motion u.

    pose: (x, y, theta) in metres, metres, radians.
    u: (rot1, trans, rot2): turn by rot1 (rad), drive trans (m) straight ahead, turn by rot2 (rad).
    Returns (x, y, theta) of the new pose; the heading is compared modulo 2*pi.
    """
    raise NotImplementedError("turn by rot1, drive trans along the new heading, turn by rot2")
