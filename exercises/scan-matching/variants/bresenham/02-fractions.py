# method: exact rational arithmetic with fractions.Fraction and floor(v + 1/2)
import math
from fractions import Fraction


def bresenham(x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    half = Fraction(1, 2)
    return [
        [x0 + math.floor(Fraction(k * dx, n) + half), y0 + math.floor(Fraction(k * dy, n) + half)]
        for k in range(n + 1)
    ]
