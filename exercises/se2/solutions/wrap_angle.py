import math


def wrap_angle(a):
    r = a - 2 * math.pi * round(a / (2 * math.pi))  # the nearest whole number of turns removed
    if r <= -math.pi:  # rounding half-way: the interval is open at -pi
        r += 2 * math.pi
    elif r > math.pi:
        r -= 2 * math.pi
    return r
