# mistake: counts the starting position as a step (k + 1 errors after k steps)
import math


def random_walk_error(sigma, steps):
    variance = 0.0
    for _ in range(steps + 1):
        variance += sigma ** 2
    return math.sqrt(variance)
