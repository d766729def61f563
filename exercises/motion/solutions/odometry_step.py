import math


def odometry_step(pose, u):
    x, y, theta = pose
    rot1, trans, rot2 = u
    return (
        x + trans * math.cos(theta + rot1),
        y + trans * math.sin(theta + rot1),
        theta + rot1 + rot2,
    )
