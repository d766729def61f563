# mistake: applies both turns before driving
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    h = t + r1 + r2
    return x + d * math.cos(h), y + d * math.sin(h), h
