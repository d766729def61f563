# method: a plain loop over the samples with random.Random(seed).gauss and math.remainder
import math
import random


def sample_motion(pose, u, alphas, n, seed):
    rnd = random.Random(seed)
    x, y, theta = pose
    rot1, trans, rot2 = u
    a1, a2, a3, a4 = alphas
    s1 = math.sqrt(a1 * rot1**2 + a2 * trans**2)
    s2 = math.sqrt(a3 * trans**2 + a4 * (rot1**2 + rot2**2))
    s3 = math.sqrt(a1 * rot2**2 + a2 * trans**2)
    out = []
    for _ in range(n):
        r1 = rot1 - rnd.gauss(0.0, s1)
        t = trans - rnd.gauss(0.0, s2)
        r2 = rot2 - rnd.gauss(0.0, s3)
        h = theta + r1
        out.append((x + t * math.cos(h), y + t * math.sin(h), math.remainder(h + r2, 2 * math.pi)))
    return out
