# mistake: closed form sum of sines, dividing by sin(rate / 2) even for a perfect heading (rate 0)
import math


def lateral_drift(step_length, heading_rate, steps):
    a = heading_rate
    n = steps
    return step_length * math.sin(n * a / 2) * math.sin((n + 1) * a / 2) / math.sin(a / 2)
