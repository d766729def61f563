# mistake: stores n as np.int32 (as for an array shape), so n ** 2 overflows for a large map
import numpy as np


def state_size(pose_dim, landmark_dim, num_landmarks):
    n = np.int32(pose_dim + landmark_dim * num_landmarks)
    return n, n**2
