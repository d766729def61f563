# mistake: sine for x and cosine for y
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    return x + d * math.sin(t + r1), y + d * math.cos(t + r1), t + r1 + r2
