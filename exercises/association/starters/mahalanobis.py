def mahalanobis(nu0, nu1, s00, s11):
    """Squared Mahalanobis distance d^2 = nu^T S^-1 nu of a 2D innovation, S diagonal.

    nu0: range innovation (m)           s00: its variance (m^2), > 0
    nu1: bearing innovation (rad)       s11: its variance (rad^2), > 0

    Returns d^2 as a float (dimensionless).
    """
    raise NotImplementedError("invert the diagonal S and form nu^T S^-1 nu")
