# mistake: treats (rot1, trans) as a world-frame displacement along rot1 only
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    return x + d * math.cos(r1), y + d * math.sin(r1), t + r1 + r2
