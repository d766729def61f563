# method: sigma times steps ** 0.5, via math.pow and math.hypot of one component
import math


def random_walk_error(sigma, steps):
    return math.hypot(sigma * math.pow(steps, 0.5), 0.0)
