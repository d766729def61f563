# mistake: integer square root of the step count (right only at perfect squares such as 400)
import math


def random_walk_error(sigma, steps):
    return sigma * math.isqrt(steps)
