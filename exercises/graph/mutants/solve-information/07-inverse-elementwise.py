# mistake: '*' instead of '@': an n x n array of products, not the vector Omega^-1 xi
import numpy as np


def solve_information(omega, xi):
    return np.linalg.inv(np.array(omega)) * np.array(xi)
