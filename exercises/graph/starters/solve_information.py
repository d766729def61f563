import numpy as np


def solve_information(omega, xi):
    """Mean of a Gaussian given in information form.

    omega: information matrix Ω, shape (n, n), symmetric positive definite (list of rows).
    xi:    information vector ξ, shape (n,).

    Returns μ, shape (n,), with Ω μ = ξ (for a 1-D pose graph: the pose estimates, in metres).
    """
    raise NotImplementedError("TODO: return the mu that solves omega @ mu = xi")
