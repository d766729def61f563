# method: closed form of a sum of sines, sin(na/2) sin((n+1)a/2) / sin(a/2), with the a = 0 case
import math


def lateral_drift(step_length, heading_rate, steps):
    a, n = heading_rate, steps
    if n == 0 or a == 0:
        return 0.0
    return step_length * math.sin(n * a / 2) * math.sin((n + 1) * a / 2) / math.sin(a / 2)
