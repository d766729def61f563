import numpy as np


def jcbb(mu, P, z, R, confidence):
    """Joint compatibility branch and bound.

    mu: state (x_r, y_r, θ_r, x_1, y_1, ..., x_N, y_N); P: its n×n covariance.
    z: m range-bearing measurements [[r, φ], ...]; R: the 2×2 noise of one measurement.
    Returns a list of m landmark indices (0-based), -1 for a measurement left unpaired: the
    jointly compatible hypothesis with the most pairings, ties to the smallest joint d².
    """
    raise NotImplementedError("depth-first over the measurements, with the bound")
