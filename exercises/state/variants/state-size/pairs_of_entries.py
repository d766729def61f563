# method: counts the covariance's entries as all ordered pairs (i, j) by a formula on blocks
import math


def state_size(pose_dim, landmark_dim, num_landmarks):
    sizes = [pose_dim] + [landmark_dim] * num_landmarks
    n = math.fsum(sizes)
    entries = sum(a * b for a in (n,) for b in sizes)
    return int(n), int(entries)
