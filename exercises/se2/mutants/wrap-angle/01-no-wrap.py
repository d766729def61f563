# mistake: the angle is returned unchanged
def wrap_angle(a):
    return a
