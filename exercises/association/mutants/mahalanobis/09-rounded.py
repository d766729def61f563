# mistake: rounds d^2 to three decimals
def mahalanobis(nu0, nu1, s00, s11):
    return round(nu0 ** 2 / s00 + nu1 ** 2 / s11, 3)
