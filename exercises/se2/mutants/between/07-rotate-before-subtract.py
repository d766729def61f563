# mistake: rotates b's position into a's frame but subtracts a's world position afterwards
import math


def between(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    x = c * b[0] + s * b[1] - a[0]
    y = -s * b[0] + c * b[1] - a[1]
    return x, y, b[2] - a[2]
