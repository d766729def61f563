# mistake: the world-frame offset b - a, not rotated into a's frame
def between(a, b):
    return b[0] - a[0], b[1] - a[1], b[2] - a[2]
