# mistake: converts the turns from degrees although they are radians
import math


def odometry_step(pose, u):
    x, y, t = pose
    r1, d, r2 = u
    r1, r2 = math.radians(r1), math.radians(r2)
    return x + d * math.cos(t + r1), y + d * math.sin(t + r1), t + r1 + r2
