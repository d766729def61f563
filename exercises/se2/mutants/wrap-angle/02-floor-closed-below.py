# mistake: floor-based wrap lands in [-pi, pi), so pi comes back as -pi
import math


def wrap_angle(a):
    return a - 2 * math.pi * math.floor((a + math.pi) / (2 * math.pi))
