# mistake: corrects by at most one turn of 2pi
import math


def wrap_angle(a):
    if a > math.pi:
        a -= 2 * math.pi
    elif a <= -math.pi:
        a += 2 * math.pi
    return a
