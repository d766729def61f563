# mistake: divides the squared innovations by the standard deviations, not the variances
import math


def mahalanobis(nu0, nu1, s00, s11):
    return nu0 ** 2 / math.sqrt(s00) + nu1 ** 2 / math.sqrt(s11)
