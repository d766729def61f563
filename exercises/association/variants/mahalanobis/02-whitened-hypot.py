# method: whiten each innovation by its standard deviation, then hypot squared
import math


def mahalanobis(nu0, nu1, s00, s11):
    return math.hypot(nu0 / math.sqrt(s00), nu1 / math.sqrt(s11)) ** 2
