# mistake: rounds the result to millimetres
import math


def random_walk_error(sigma, steps):
    return round(sigma * math.sqrt(steps), 3)
