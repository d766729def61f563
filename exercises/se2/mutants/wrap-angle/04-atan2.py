# mistake: atan2(sin a, cos a) returns -pi for -pi, outside (-pi, pi]
import math


def wrap_angle(a):
    return math.atan2(math.sin(a), math.cos(a))
