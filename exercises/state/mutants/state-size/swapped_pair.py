# mistake: returns the pair in the wrong order, (entries, n)
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim + landmark_dim * num_landmarks
    return n * n, n
