def state_size(pose_dim, landmark_dim, num_landmarks):
    """Sizes of an EKF-SLAM state and of its covariance.

    pose_dim:      numbers in the robot pose (3 in 2D: x, y, heading)       -- int >= 1
    landmark_dim:  numbers per landmark (2 in 2D: x, y)                     -- int >= 1
    num_landmarks: landmarks on the map                                     -- int >= 0

    Returns (n, entries): n is the length of the state vector x, entries the number of
    entries of the covariance matrix Sigma. Both are ints; a tuple or a list is fine.
    """
    raise NotImplementedError("compute n, then the size of the n x n covariance")
