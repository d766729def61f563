# mistake: loops with >= and < wrap into [-pi, pi)
import math


def wrap_angle(a):
    while a >= math.pi:
        a -= 2 * math.pi
    while a < -math.pi:
        a += 2 * math.pi
    return a
