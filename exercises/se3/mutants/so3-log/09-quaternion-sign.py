# mistake: the quaternion route without choosing qw >= 0, so some angles come out in (pi, 2 pi)
import math

import numpy as np


def so3_log(R):
    m = np.array(R, dtype=float)
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    squares = [1 + tr, 1 + 2 * m[0, 0] - tr, 1 + 2 * m[1, 1] - tr, 1 + 2 * m[2, 2] - tr]
    k = int(np.argmax(squares))
    big = math.sqrt(squares[k]) / 2
    f = 4 * big
    if k == 0:
        q = [big, (m[2, 1] - m[1, 2]) / f, (m[0, 2] - m[2, 0]) / f, (m[1, 0] - m[0, 1]) / f]
    elif k == 1:
        q = [(m[2, 1] - m[1, 2]) / f, big, (m[0, 1] + m[1, 0]) / f, (m[0, 2] + m[2, 0]) / f]
    elif k == 2:
        q = [(m[0, 2] - m[2, 0]) / f, (m[0, 1] + m[1, 0]) / f, big, (m[1, 2] + m[2, 1]) / f]
    else:
        q = [(m[1, 0] - m[0, 1]) / f, (m[0, 2] + m[2, 0]) / f, (m[1, 2] + m[2, 1]) / f, big]
    q = np.array(q)
    v = q[1:]
    s = np.linalg.norm(v)
    if s == 0:
        return np.zeros(3)
    return 2 * math.atan2(s, q[0]) / s * v
