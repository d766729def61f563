# mistake: the Euclidean length squared, S ignored
def mahalanobis(nu0, nu1, s00, s11):
    return nu0 ** 2 + nu1 ** 2
