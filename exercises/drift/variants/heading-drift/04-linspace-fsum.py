# method: numpy linspace of the step headings, summed with math.fsum
import math

import numpy as np


def lateral_drift(step_length, heading_rate, steps):
    headings = np.linspace(heading_rate, heading_rate * steps, steps)
    return math.fsum(step_length * np.sin(headings))
