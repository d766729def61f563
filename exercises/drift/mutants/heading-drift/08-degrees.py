# mistake: treats the heading rate as degrees and converts it to radians again
import math


def lateral_drift(step_length, heading_rate, steps):
    return sum(step_length * math.sin(math.radians(heading_rate * k)) for k in range(1, steps + 1))
