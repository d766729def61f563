# mistake: |nu| / s instead of nu^2 / s
def mahalanobis(nu0, nu1, s00, s11):
    return abs(nu0) / s00 + abs(nu1) / s11
