# mistake: counts only the pose block and the landmark block, forgetting the cross-covariances
def state_size(pose_dim, landmark_dim, num_landmarks):
    m = landmark_dim * num_landmarks
    return pose_dim + m, pose_dim * pose_dim + m * m
