# mistake: counts only the off-diagonal covariances, n*n - n, leaving out the variances
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim + landmark_dim * num_landmarks
    return n, n * n - n
