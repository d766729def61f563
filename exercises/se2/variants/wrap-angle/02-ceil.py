# method: subtract ceil((a - pi) / 2pi) whole turns
import math


def wrap_angle(a):
    return a - 2 * math.pi * math.ceil((a - math.pi) / (2 * math.pi))
