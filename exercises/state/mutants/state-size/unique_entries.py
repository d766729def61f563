# mistake: counts the distinct entries of the symmetric covariance, n(n+1)/2, not all n*n
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim + landmark_dim * num_landmarks
    return n, n * (n + 1) // 2
