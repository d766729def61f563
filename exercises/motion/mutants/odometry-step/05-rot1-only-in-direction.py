# mistake: the first turn sets the direction of travel but is not added to the final heading
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    return x + d * math.cos(t + r1), y + d * math.sin(t + r1), t + r2
