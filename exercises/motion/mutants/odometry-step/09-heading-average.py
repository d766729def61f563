# mistake: drives along the mean of the start and end headings (a velocity-model habit)
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    h = t + (r1 + r2) / 2
    return x + d * math.cos(h), y + d * math.sin(h), t + r1 + r2
