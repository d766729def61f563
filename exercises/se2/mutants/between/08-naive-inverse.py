# mistake: inverts a by negating its components, then composes
import math


def between(a, b):
    ia = (-a[0], -a[1], -a[2])
    c, s = math.cos(ia[2]), math.sin(ia[2])
    return ia[0] + c * b[0] - s * b[1], ia[1] + s * b[0] + c * b[1], ia[2] + b[2]
