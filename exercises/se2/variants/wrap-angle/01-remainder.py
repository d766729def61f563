# method: math.remainder (exact, in [-pi, pi]) with -pi mapped to pi
import math


def wrap_angle(a):
    r = math.remainder(a, 2 * math.pi)
    return math.pi if r == -math.pi else r
