# mistake: divides both terms by the range variance
def mahalanobis(nu0, nu1, s00, s11):
    return (nu0 * nu0 + nu1 * nu1) / s00
