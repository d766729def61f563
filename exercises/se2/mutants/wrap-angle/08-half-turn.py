# mistake: removes multiples of pi instead of 2pi (flips the direction for odd counts)
import math


def wrap_angle(a):
    r = math.remainder(a, math.pi)
    return r
