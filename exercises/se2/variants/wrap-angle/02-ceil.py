# method: subtract ceil((a - pi) / 2pi) whole turns, then one turn more where rounding left the result just beyond pi
import math


def wrap_angle(a):
    r = a - 2 * math.pi * math.ceil((a - math.pi) / (2 * math.pi))
    return r - 2 * math.pi if r > math.pi else r
