# mistake: a special case for one pose that returns xi itself (forgetting to divide by Omega_00)
import numpy as np


def solve_information(omega, xi):
    if len(xi) == 1:
        return list(xi)
    return np.linalg.solve(np.array(omega), np.array(xi))
