# method: exp(log) form with an explicit zero case (sqrt(k) = exp(log(k) / 2))
import math


def random_walk_error(sigma, steps):
    if steps == 0:
        return 0.0
    return math.exp(math.log(sigma) + 0.5 * math.log(steps))
