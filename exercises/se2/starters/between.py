import math


def between(a, b):
    """Pose b seen from pose a: a^-1 (+) b.

    a, b: (x, y, theta) with x, y in metres and theta in radians (world frame).
    Returns (x, y, theta): b's position in a's frame (x ahead of a, y to its left) and the
    change of heading from a to b (radians; compared modulo 2*pi).
    """
    raise NotImplementedError("rotate the world offset b - a into a's frame")
