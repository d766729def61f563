# method: the whitened innovation as a complex number, abs squared
import math


def mahalanobis(nu0, nu1, s00, s11):
    w = complex(nu0 / math.sqrt(s00), nu1 / math.sqrt(s11))
    return abs(w) ** 2
