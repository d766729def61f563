import math


def wrap_angle(a):
    """The angle a (radians, any finite value) wrapped into (-pi, pi].

    Returns a float r with -pi < r <= pi and r = a + 2*pi*k for some whole number k.
    """
    raise NotImplementedError("remove whole turns of 2*pi until the angle is in (-pi, pi]")
