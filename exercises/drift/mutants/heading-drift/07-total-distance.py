# mistake: returns the distance from the intended end point (total error), not the sideways part
import math


def lateral_drift(step_length, heading_rate, steps):
    x = y = 0.0
    for k in range(1, steps + 1):
        x += step_length * math.cos(heading_rate * k)
        y += step_length * math.sin(heading_rate * k)
    return math.hypot(steps * step_length - x, y)
