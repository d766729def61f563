# mistake: counts the landmarks only and leaves the robot pose out of the state
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = landmark_dim * num_landmarks
    return n, n * n
