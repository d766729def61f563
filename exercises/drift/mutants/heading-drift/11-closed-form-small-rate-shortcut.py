# mistake: the closed form of the sum of sines, and below 0.01 rad per step (where dividing by sin(rate/2) looks risky) the small-angle sum rate * n(n+1)/2, which is far off after many steps
import math


def lateral_drift(step_length, heading_rate, steps):
    if abs(heading_rate) < 0.01:
        return step_length * heading_rate * steps * (steps + 1) / 2
    half = heading_rate / 2
    return step_length * math.sin(steps * half) * math.sin((steps + 1) * half) / math.sin(half)
