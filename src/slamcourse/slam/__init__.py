"""Reference mathematics of the bundled course, written to read like the chapters.

Each module is one topic's mathematics, typed, with shapes and units in its docstrings:
``association`` (Mahalanobis distance, χ² gate), ``drift`` (how odometry error accumulates and
how a loop closure spreads its correction), ``graph`` (the information form of a pose graph),
``vision`` (epipolar geometry, RANSAC counts), ``factor`` (elimination and fill-in),
``occupancy`` (log-odds grids), ``capstone`` (sizing a 2D LiDAR SLAM system); beyond the lesson,
``se2`` (poses in the plane), ``ekf`` (motion model and prediction), ``posegraph`` (errors,
Jacobians and Gauss-Newton, the INTEL capstone), ``ekfslam`` (the EKF-SLAM update and landmark
initialisation), ``jcbb`` (joint compatibility), ``consistency`` (NEES and NIS). Chapters'
``exercises/<chapter>/reference.py`` files call these functions; the engine itself never imports
this package (it holds no answers of its own).
"""
