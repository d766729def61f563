# mistake: range(1, steps) stops one step short
import math


def lateral_drift(step_length, heading_rate, steps):
    total = 0.0
    for k in range(1, steps):
        total += step_length * math.sin(heading_rate * k)
    return total
