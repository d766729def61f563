# mistake: int() truncates towards zero, leaving results in (-2pi, 2pi)
import math


def wrap_angle(a):
    return a - 2 * math.pi * int(a / (2 * math.pi))
