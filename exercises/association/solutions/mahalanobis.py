def mahalanobis(nu0, nu1, s00, s11):
    range_term = nu0 * nu0 / s00
    bearing_term = nu1 * nu1 / s11
    return range_term + bearing_term
