# method: numpy complex exponentials: the imaginary part of sum(L * exp(i a k))
import numpy as np


def lateral_drift(step_length, heading_rate, steps):
    k = np.arange(1, steps + 1)
    return (step_length * np.exp(1j * heading_rate * k)).sum().imag
