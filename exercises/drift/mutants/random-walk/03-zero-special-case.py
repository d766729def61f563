# mistake: special-cases "no steps" as one step's error
import math


def random_walk_error(sigma, steps):
    if steps == 0:
        return sigma
    return sigma * math.sqrt(steps)
