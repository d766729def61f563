# mistake: counts in a numpy int32 array, so n * n wraps around past 2**31 for a large map (100 000 landmarks)
import numpy as np


def state_size(pose_dim, landmark_dim, num_landmarks):
    dims = np.array([pose_dim, landmark_dim, num_landmarks], dtype=np.int32)
    n = dims[0] + dims[1] * dims[2]
    return int(n), int(n * n)
