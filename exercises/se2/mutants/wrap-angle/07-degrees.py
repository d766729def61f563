# mistake: wraps as if the angle were in degrees (a full turn of 360)
def wrap_angle(a):
    while a > 180:
        a -= 360
    while a <= -180:
        a += 360
    return a
