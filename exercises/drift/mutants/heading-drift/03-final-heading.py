# mistake: drives the whole distance at the final heading error
import math


def lateral_drift(step_length, heading_rate, steps):
    return steps * step_length * math.sin(heading_rate * steps)
