# method: a plain loop adding one step's variance at a time, then the square root
import math


def random_walk_error(sigma, steps):
    variance = 0.0
    for _ in range(steps):
        variance += sigma * sigma
    return math.sqrt(variance)
