# mistake: caps d^2 at a million "to avoid overflow" (any such candidate is rejected anyway)
def mahalanobis(nu0, nu1, s00, s11):
    d2 = nu0 * nu0 / s00 + nu1 * nu1 / s11
    return min(d2, 1e6)
