import math


def random_walk_error(sigma, steps):
    variance = steps * sigma ** 2
    return math.sqrt(variance)
