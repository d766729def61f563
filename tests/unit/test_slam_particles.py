"""``slamcourse.slam.particles`` against independent computations: closed-form moments, brute
force from the definitions, scipy's densities and the information form of the EKF."""

from __future__ import annotations

import itertools
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from scipy.stats import chi2, multivariate_normal, norm

from slamcourse.plots import ch_particles
from slamcourse.slam import particles as pf


def test_noise_sd_by_hand() -> None:
    # σ²rot1 = 0.01·0.09 + 0.005·1, σ²trans = 0.005·1 + 0.0001·(0.09 + 0.04), σ²rot2 likewise
    sd = pf.odometry_noise_sd((0.3, 1.0, -0.2), (0.01, 0.005, 0.005, 0.0001))
    assert sd == pytest.approx(
        (math.sqrt(0.0059), math.sqrt(0.005 + 0.000013), math.sqrt(0.0004 + 0.005))
    )


def test_sample_mean_matches_the_closed_form() -> None:
    # E[t̂ cos(a + ε1)] = t cos(a) exp(−σ1²/2) for ε1 ~ N(0, σ1²) independent of t̂
    pose, u, alphas = (1.0, -2.0, 0.4), (0.5, 1.5, 0.3), (0.05, 0.02, 0.01, 0.001)
    s1, s2, _ = pf.odometry_noise_sd(u, alphas)
    p = pf.sample_motion(pose, u, alphas, 200_000, np.random.default_rng(0))
    a = pose[2] + u[0]
    damp = math.exp(-(s1**2) / 2)
    assert p[:, 0].mean() == pytest.approx(pose[0] + u[1] * math.cos(a) * damp, abs=0.004)
    assert p[:, 1].mean() == pytest.approx(pose[1] + u[1] * math.sin(a) * damp, abs=0.004)
    # Var(x') = E[t̂²] E[cos²] − (E[t̂ cos])², E[cos²(a+ε)] = (1 + cos 2a · e^{−2σ²}) / 2
    cos2 = (1 + math.cos(2 * a) * math.exp(-2 * s1**2)) / 2
    var_x = (u[1] ** 2 + s2**2) * cos2 - (u[1] * math.cos(a) * damp) ** 2
    assert p[:, 0].var() == pytest.approx(var_x, rel=0.02)
    assert np.all(np.abs(p[:, 2]) <= math.pi)


def test_noise_is_recovered_exactly() -> None:
    pose, u, alphas = (10.0, 5.0, 3.0), (0.2, 0.8, 0.3), (0.01, 0.01, 0.004, 0.0001)
    sd = np.array(pf.odometry_noise_sd(u, alphas))
    drawn = np.random.default_rng(5).normal(size=(500, 3)) * sd  # the draw sample_motion makes
    p = pf.sample_motion(pose, u, alphas, 500, np.random.default_rng(5))
    assert pf.noise_from_samples(pose, u, p) == pytest.approx(drawn, abs=1e-12)


def test_noise_test_thresholds_are_the_exact_quantiles() -> None:
    t = pf.NoiseTest(9e-6)
    assert t.z == pytest.approx(norm.ppf(1 - 0.5e-6))
    lo, hi = t.chi2_window(100)
    assert chi2.cdf(lo, 100) == pytest.approx(0.5e-6) and chi2.sf(hi, 100) == pytest.approx(0.5e-6)


def test_a_correct_sampler_is_rejected_at_most_at_the_stated_rate() -> None:
    # at alpha = 0.05 the rejection rate of true Gaussian noise stays below 5 % (Bonferroni)
    rng = np.random.default_rng(11)
    sd = (0.1, 0.02, 0.3)
    trials = 3000
    rejected = sum(
        pf.check_gaussian_noise(rng.normal(size=(60, 3)) * sd, sd, 0.05) is not None
        for _ in range(trials)
    )
    assert rejected / trials < 0.05 + 3 * math.sqrt(0.05 * 0.95 / trials)


@pytest.mark.parametrize(
    ("scale", "shared", "words"),
    [((1.3, 1, 1), False, "standard deviation"), ((1, 1, 1), True, "not independent")],
)
def test_wrong_noise_is_rejected(scale: tuple[float, ...], shared: bool, words: str) -> None:
    sd = (0.1, 0.02, 0.3)
    z = np.random.default_rng(3).normal(size=(1000, 3))
    if shared:
        z[:, 2] = z[:, 0]
    message = pf.check_gaussian_noise(z * np.array(sd) * scale, sd, 1e-6)
    assert message is not None and words in message


def test_zero_noise_must_be_zero() -> None:
    e = np.zeros((10, 3))
    assert pf.check_gaussian_noise(e, (0.0, 0.0, 0.0), 1e-6) is None
    e[3, 1] = 1e-6
    assert "no noise" in (pf.check_gaussian_noise(e, (0.0, 0.0, 0.0), 1e-6) or "")


def _brute_resample(weights: list[float], u: float) -> list[int]:
    """The definition: particle m takes the i with c_{i−1} < (u + m)/N ≤ c_i, exact fractions."""
    from fractions import Fraction

    w = [Fraction(v) for v in weights]
    total = sum(w)
    n = len(w)
    out = []
    for m in range(n):
        t = (Fraction(u) + m) / n
        acc = Fraction(0)
        for i, v in enumerate(w):
            if acc < t <= acc + v / total:
                out.append(i)
                break
            acc += v / total
    return out


def test_low_variance_resample_is_the_definition() -> None:
    assert pf.low_variance_resample([0.1, 0.4, 0.3, 0.2], 0.5).tolist() == [1, 1, 2, 3]
    rng = np.random.default_rng(2)
    for _ in range(300):
        n = int(rng.integers(1, 30))
        w = np.where(rng.uniform(size=n) < 0.2, 0.0, rng.uniform(0, 5, n))
        if w.sum() == 0:
            continue
        u = float(rng.uniform())
        if pf.nearest_tie(w, u) < 1e-9:
            continue
        assert pf.low_variance_resample(w, u).tolist() == _brute_resample(w.tolist(), u)


def test_low_variance_copies_are_floor_or_ceiling() -> None:
    rng = np.random.default_rng(4)
    w = pf.normalise(rng.uniform(size=40))
    for u in rng.uniform(size=20):
        kept = pf.copies(pf.low_variance_resample(w, float(u)), 40)
        assert np.all((kept == np.floor(40 * w)) | (kept == np.ceil(40 * w)))


def test_effective_sample_size() -> None:
    assert pf.effective_sample_size([1, 1, 1, 1]) == pytest.approx(4)
    assert pf.effective_sample_size([0, 3, 0]) == pytest.approx(1)


def test_likelihood_is_scipys_density() -> None:
    s = np.array([[0.02, 0.003], [0.003, 0.004]])
    nu = np.array([0.1, -0.05])
    assert pf.gaussian_likelihood(nu, s) == pytest.approx(
        multivariate_normal(mean=[0, 0], cov=s).pdf(nu)
    )


def test_landmark_update_equals_the_information_form() -> None:
    pose, mu, sigma = (1.0, 2.0, 0.3), np.array([4.0, 5.0]), np.array([[0.3, 0.05], [0.05, 0.2]])
    q = np.diag([0.01, 0.0025])
    z = pf.range_bearing(pose, mu) + np.array([0.15, -0.04])
    upd = pf.landmark_update(pose, mu, sigma, z, q)
    h = pf.observation_jacobian(pose, mu)
    info = np.linalg.inv(sigma) + h.T @ np.linalg.inv(q) @ h
    cov = np.linalg.inv(info)
    nu = pf.innovation(z, pf.range_bearing(pose, mu))
    assert upd.cov == pytest.approx(cov)
    assert upd.mean == pytest.approx(mu + cov @ h.T @ np.linalg.inv(q) @ nu)
    # H by central differences
    eps = 1e-6
    num_h = np.column_stack(
        [
            (pf.range_bearing(pose, mu + d) - pf.range_bearing(pose, mu - d)) / (2 * eps)
            for d in (np.array([eps, 0]), np.array([0, eps]))
        ]
    )
    assert h == pytest.approx(num_h, abs=1e-7)


def test_multinomial_loss_matches_the_formula() -> None:
    # with equal weights a particle gets no copy with probability (1 − 1/N)^N
    rng = np.random.default_rng(8)
    lost = [
        100 - len(set(pf.multinomial_resample(np.ones(100), rng).tolist())) for _ in range(2000)
    ]
    assert np.mean(lost) / 100 == pytest.approx((1 - 1 / 100) ** 100, abs=0.005)


def test_figures_are_accessible_svg() -> None:
    for draw in ch_particles.FIGURES.values():
        root = ET.fromstring(draw())
        ns = "{http://www.w3.org/2000/svg}"
        assert root.find(f"{ns}title") is not None and root.find(f"{ns}desc") is not None
    for picture in ch_particles.PICTURES.values():
        ET.fromstring(picture.draw({}, False))


def test_figure_facts() -> None:
    assert ch_particles.distinct_ancestors(50, 40, "low-variance") == [50] * 40
    multi = ch_particles.distinct_ancestors(50, 40, "multinomial")
    assert all(a >= b for a, b in itertools.pairwise(multi)) and multi[-1] < 10
    last = ch_particles.cloud_steps()[-1]
    assert last[:, 1].std() > 2 * last[:, 0].std()  # wider across the drive than along it
    assert last[:, 0].mean() < ch_particles.CLOUD_STEPS * ch_particles.CLOUD_U[1]  # short of it
