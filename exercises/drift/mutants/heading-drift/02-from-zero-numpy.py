# mistake: np.arange(steps) runs k = 0 .. steps-1, so the first step has no heading error
import numpy as np


def lateral_drift(step_length, heading_rate, steps):
    k = np.arange(steps)
    return float(np.sum(step_length * np.sin(heading_rate * k)))
