import math


def lateral_drift(step_length, heading_rate, steps):
    """Sideways error (m) after driving 'straight' with a growing heading error.

    step_length:  length of each step (m)
    heading_rate: heading error added per step (rad); step k is driven heading_rate * k
                  radians off course (k = 1 .. steps)
    steps:        number of steps (int >= 0)

    Returns the total sideways displacement (m), a float.
    """
    raise NotImplementedError("add up each step's sideways move")
