# mistake: adds a tiny epsilon to the variances "to avoid dividing by zero"
EPS = 1e-9


def mahalanobis(nu0, nu1, s00, s11):
    return nu0 ** 2 / (s00 + EPS) + nu1 ** 2 / (s11 + EPS)
