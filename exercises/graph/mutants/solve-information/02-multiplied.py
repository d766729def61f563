# mistake: multiplies by Omega instead of solving (Omega xi, not Omega^-1 xi)
import numpy as np


def solve_information(omega, xi):
    return np.array(omega) @ np.array(xi)
