def mahalanobis(nu0, nu1, s00, s11):
    """Squared Mahalanobis distance d^2 = nu^T S^-1 nu of a 2D innovation, S diagonal.

    nu0: range innovation (m), -50 to 50       s00: its variance (m^2), 1e-6 to 100
    nu1: bearing innovation (rad), -pi to pi   s11: its variance (rad^2), 1e-8 to 1

    Returns d^2 as a float (dimensionless).
    """
    raise NotImplementedError("invert the diagonal S and form nu^T S^-1 nu")
