# mistake: a - 2pi*round(a/2pi) rounds halves to even, so -pi stays -pi
import math


def wrap_angle(a):
    return a - 2 * math.pi * round(a / (2 * math.pi))
