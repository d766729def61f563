# mistake: off by one landmark, counting num_landmarks - 1 landmarks after the pose
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim + landmark_dim * max(num_landmarks - 1, 0)
    return n, n * n
