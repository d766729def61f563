# mistake: uses sin x ≈ x "where it is accurate enough" (below 0.1 rad) and the sine above
import math


def lateral_drift(step_length, heading_rate, steps):
    total = 0.0
    for k in range(1, steps + 1):
        angle = heading_rate * k
        total += step_length * (angle if abs(angle) < 0.1 else math.sin(angle))
    return total
