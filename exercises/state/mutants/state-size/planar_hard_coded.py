# mistake: hard-codes the planar layout of the chapter (pose 3, landmark 2) and ignores the dims
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = 3 + 2 * num_landmarks
    return n, n * n
