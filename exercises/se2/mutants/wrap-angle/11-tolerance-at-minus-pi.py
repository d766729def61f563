# mistake: treats every result within 1e-9 of -pi as -pi itself, so angles just inside the interval come back as pi
import math


def wrap_angle(a):
    r = math.remainder(a, 2 * math.pi)
    if abs(r + math.pi) < 1e-9:
        return math.pi
    return r
