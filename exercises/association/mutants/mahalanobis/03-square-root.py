# mistake: returns d, the square root of the asked d^2
import math


def mahalanobis(nu0, nu1, s00, s11):
    return math.sqrt(nu0 ** 2 / s00 + nu1 ** 2 / s11)
