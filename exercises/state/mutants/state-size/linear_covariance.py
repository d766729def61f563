# mistake: thinks the covariance stores one variance per state entry, so entries = n
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim + landmark_dim * num_landmarks
    return n, n
