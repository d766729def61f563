# mistake: a % 2pi lands in [0, 2pi)
import math


def wrap_angle(a):
    return a % (2 * math.pi)
