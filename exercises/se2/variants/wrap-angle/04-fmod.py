# method: math.fmod (exact, keeps the sign of a), then one turn added or removed
import math


def wrap_angle(a):
    r = math.fmod(a, 2 * math.pi)
    if r > math.pi:
        r -= 2 * math.pi
    elif r <= -math.pi:
        r += 2 * math.pi
    return r
