# method: variances add, math.sqrt of k * sigma**2
import math


def random_walk_error(sigma, steps):
    return math.sqrt(steps * sigma * sigma)
