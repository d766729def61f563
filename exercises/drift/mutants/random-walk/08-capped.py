# mistake: caps the error at 100 m ("a robot never gets further off than that")
import math


def random_walk_error(sigma, steps):
    return min(sigma * math.sqrt(steps), 100.0)
