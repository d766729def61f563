"""Reference answers for chapter ``state``: the size of the EKF-SLAM state and its covariance.

The state stacks the robot pose (``pose_dim`` numbers) and every landmark (``landmark_dim``
numbers each)::

    x = [x_r, y_r, θ_r, x_1, y_1, ..., x_N, y_N]      (2D: pose_dim = 3, landmark_dim = 2)

so ``x`` has ``n = pose_dim + landmark_dim · N`` entries and its covariance ``Σ`` is ``n × n``.
Every function takes the exercise's parameters as keyword arguments and returns a plain number.
Functions whose name starts with ``mistake_`` compute the wrong answer a learner with a named
misconception would give.
"""

from __future__ import annotations


def state_dimension(num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """Length ``n`` of the state vector: the pose plus ``landmark_dim`` numbers per landmark."""
    return pose_dim + landmark_dim * num_landmarks


def covariance_entry_count(num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """Number of entries of the ``n × n`` covariance ``Σ``: ``n²``."""
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return n * n


def unique_covariance_entries(num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """Entries of the symmetric ``Σ`` that are free to differ: the diagonal plus one triangle.

    ``n`` diagonal entries plus ``n(n − 1)/2`` above it give ``n(n + 1)/2``.
    """
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return n * (n + 1) // 2


def covariance_growth_factor(
    few_landmarks: int, many_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> float:
    """How many times more entries ``Σ`` has with ``many_landmarks`` than with ``few_landmarks``."""
    return covariance_entry_count(many_landmarks, pose_dim, landmark_dim) / covariance_entry_count(
        few_landmarks, pose_dim, landmark_dim
    )


def landmark_x_index(landmark: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """1-based position of ``x_j`` (landmark ``landmark``'s first coordinate) in the state vector.

    The pose fills positions ``1 … pose_dim``; landmark ``j`` starts after ``j − 1`` whole
    landmarks.
    """
    return pose_dim + landmark_dim * (landmark - 1) + 1


# --- misconceptions -------------------------------------------------------------------------


def mistake_pose_forgotten_size(
    num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> int:
    """State size counting the landmarks only (the robot pose left out)."""
    return landmark_dim * num_landmarks


def mistake_heading_forgotten_size(
    num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> int:
    """State size with a 2-number pose (position without the heading θ_r)."""
    return 2 + landmark_dim * num_landmarks


def mistake_state_size_not_squared(
    num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> int:
    """The state size ``n`` given where the covariance's ``n²`` entries were asked for."""
    return state_dimension(num_landmarks, pose_dim, landmark_dim)


def mistake_pose_forgotten_entries(
    num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> int:
    """Covariance entries of a landmarks-only state: ``(landmark_dim · N)²``."""
    return (landmark_dim * num_landmarks) ** 2


def mistake_planar_sizes_entries(
    num_landmarks: int, pose_dim: int = 6, landmark_dim: int = 3
) -> int:
    """Covariance entries computed with the 2D sizes (3-number pose, 2 per landmark)."""
    return covariance_entry_count(num_landmarks, 3, 2)


def mistake_diagonal_forgotten(num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """``n(n − 1)/2``: the strict upper triangle, without the diagonal."""
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return n * (n - 1) // 2


def mistake_all_entries(num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """``n²``: every entry, ignoring the symmetry."""
    return covariance_entry_count(num_landmarks, pose_dim, landmark_dim)


def mistake_linear_growth(
    few_landmarks: int, many_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> float:
    """Growth taken as linear in the number of landmarks: ``N_many / N_few``."""
    return many_landmarks / few_landmarks


def mistake_state_growth(
    few_landmarks: int, many_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> float:
    """Growth of the state size ``n`` instead of the covariance's ``n²``."""
    return state_dimension(many_landmarks, pose_dim, landmark_dim) / state_dimension(
        few_landmarks, pose_dim, landmark_dim
    )


def mistake_landmarks_only_growth(
    few_landmarks: int, many_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> float:
    """``(N_many / N_few)²``: quadratic, but with the robot pose left out of ``n``."""
    return (many_landmarks / few_landmarks) ** 2


def mistake_zero_based_index(landmark: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """0-based position of ``x_j`` where a 1-based position was asked for."""
    return landmark_x_index(landmark, pose_dim, landmark_dim) - 1


def mistake_index_pose_forgotten(landmark: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """1-based position of ``x_j`` in a landmarks-only vector (the pose not counted)."""
    return landmark_dim * (landmark - 1) + 1


# --- code exercise ``state/state-size`` -----------------------------------------------------


def state_size(pose_dim: int, landmark_dim: int, num_landmarks: int) -> tuple[int, int]:
    """``(n, n²)``: the state length and the number of entries of its ``n × n`` covariance."""
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return n, covariance_entry_count(num_landmarks, pose_dim, landmark_dim)


def state_size_pose_forgotten(
    pose_dim: int, landmark_dim: int, num_landmarks: int
) -> tuple[int, int]:
    """Wrong: the sizes of a landmarks-only state (the robot pose left out)."""
    n = landmark_dim * num_landmarks
    return n, n * n


def state_size_unique_entries(
    pose_dim: int, landmark_dim: int, num_landmarks: int
) -> tuple[int, int]:
    """Wrong: the covariance counted as its ``n(n + 1)/2`` distinct entries, not all ``n²``."""
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return n, unique_covariance_entries(num_landmarks, pose_dim, landmark_dim)


def state_size_one_landmark_dim(
    pose_dim: int, landmark_dim: int, num_landmarks: int
) -> tuple[int, int]:
    """Wrong: one number per landmark (``landmark_dim`` ignored)."""
    n = pose_dim + num_landmarks
    return n, n * n


def mistake_half_rounded_down(
    num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2
) -> int:
    """``⌊n²/2⌋``: all entries halved (the diagonal too), rounded down to a whole count."""
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return n * n // 2


def mistake_half_rounded_up(num_landmarks: int, pose_dim: int = 3, landmark_dim: int = 2) -> int:
    """``⌈n²/2⌉``: all entries halved (the diagonal too), rounded up to a whole count."""
    n = state_dimension(num_landmarks, pose_dim, landmark_dim)
    return -(-n * n // 2)
