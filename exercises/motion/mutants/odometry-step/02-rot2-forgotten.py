# mistake: the final heading misses the second turn
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    return x + d * math.cos(t + r1), y + d * math.sin(t + r1), t + r1
