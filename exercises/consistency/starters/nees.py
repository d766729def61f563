import math

import numpy as np


def nees(x_true, x_hat, P):
    """Normalised estimation error squared eᵀ P⁻¹ e with e = x_true − x_hat.

    x_true, x_hat: states (x_r, y_r, θ_r, x_1, y_1, ...); metres, the heading (entry 2) in rad.
    P: the covariance of x_hat (nested lists). Wrap the heading error into (−π, π].
    """
    raise NotImplementedError("compute the error, wrap its heading, then eᵀ P⁻¹ e")
