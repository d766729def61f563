# method: add or subtract 2pi in loops, with the boundary tests > pi and <= -pi
import math


def wrap_angle(a):
    while a > math.pi:
        a -= 2 * math.pi
    while a <= -math.pi:
        a += 2 * math.pi
    return a
