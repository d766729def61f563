# method: pose composition: pose (+) (0, 0, rot1) (+) (trans, 0, rot2)
import math


def compose(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


def odometry_step(pose, u):
    rot1, trans, rot2 = u
    return compose(compose(pose, (0.0, 0.0, rot1)), (trans, 0.0, rot2))
