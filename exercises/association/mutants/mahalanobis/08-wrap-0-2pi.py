# mistake: "wraps" the bearing innovation into [0, 2π), turning a small negative one into almost 2π
import math


def mahalanobis(nu0, nu1, s00, s11):
    nu1 = nu1 % (2 * math.pi)
    return nu0 ** 2 / s00 + nu1 ** 2 / s11
