# mistake: adds the forward component (cos) instead of the sideways one
import math


def lateral_drift(step_length, heading_rate, steps):
    total = 0.0
    for k in range(1, steps + 1):
        total += step_length * math.cos(heading_rate * k)
    return total
