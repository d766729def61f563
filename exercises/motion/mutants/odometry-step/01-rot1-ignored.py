# mistake: drives along the old heading theta, ignoring the first turn
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    return x + d * math.cos(t), y + d * math.sin(t), t + r1 + r2
