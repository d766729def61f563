# mistake: gives each landmark one number in the state instead of landmark_dim numbers
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim + num_landmarks
    return n, n * n
