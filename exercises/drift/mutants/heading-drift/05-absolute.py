# mistake: returns the size of the error, abs(), losing the side (right drift is negative)
import math


def lateral_drift(step_length, heading_rate, steps):
    total = 0.0
    for k in range(1, steps + 1):
        total += step_length * math.sin(heading_rate * k)
    return abs(total)
