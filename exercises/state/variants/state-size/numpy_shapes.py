# method: numpy block sizes, and the covariance's entry count as the product of its shape
import numpy as np


def state_size(pose_dim, landmark_dim, num_landmarks):
    blocks = np.array([pose_dim] + [landmark_dim] * num_landmarks)
    n = int(blocks.sum())
    return np.array([n, np.prod((n, n))])
