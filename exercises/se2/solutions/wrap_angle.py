import math


def wrap_angle(a):
    turns = math.ceil((a - math.pi) / (2 * math.pi))
    return a - 2 * math.pi * turns
