# mistake: reads s00, s11 as standard deviations and squares them again
def mahalanobis(nu0, nu1, s00, s11):
    return nu0 ** 2 / s00 ** 2 + nu1 ** 2 / s11 ** 2
