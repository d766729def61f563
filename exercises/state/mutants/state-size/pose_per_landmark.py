# mistake: repeats the pose with every landmark, (pose_dim + landmark_dim) * num_landmarks
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = (pose_dim + landmark_dim) * num_landmarks
    return n, n * n
