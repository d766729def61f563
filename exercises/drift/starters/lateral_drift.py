import math


def lateral_drift(step_length, heading_rate, steps):
    """Sideways error (m) after driving 'straight' with a growing heading error.

    step_length:  length of each step (m), 0.01 to 2
    heading_rate: heading error added per step (rad), -0.05 to 0.05 (negative: to the right);
                  step k is driven heading_rate * k radians off course (k = 1 .. steps)
    steps:        number of steps (int, 0 to 2000)

    Returns the total sideways displacement (m, positive to the left), a float.
    """
    raise NotImplementedError("add up each step's sideways move")
