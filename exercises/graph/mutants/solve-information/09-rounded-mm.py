# mistake: the estimate rounded to millimetres "for display"
import numpy as np


def solve_information(omega, xi):
    return np.round(np.linalg.solve(np.array(omega), np.array(xi)), 3)
