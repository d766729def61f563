import math


def random_walk_error(sigma, steps):
    """1-sigma position error after independent odometry steps.

    sigma: standard deviation of one step's error (m), 0.0001 to 1
    steps: number of steps (int, 0 to 1_000_000)

    Returns the standard deviation (m) of the accumulated error, a float.
    """
    raise NotImplementedError("add the variances of the steps, then take the square root")
