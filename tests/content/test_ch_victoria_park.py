"""Content tests of chapter ``victoria-park`` (landmark SLAM on the Victoria Park data set).

1. every figure the prose (and the exercises' texts) quote, recomputed here by independent
   code: its own reader, errors from homogeneous SE(2) matrices, Jacobians by central
   differences, its own sparse Gauss-Newton and batches, its own EKF (augmented with the x-y
   inverse model directly), a stochastic trace estimate of the redundancies; and compared with
   the reference code;
2. the figures and pictures draw (SVG with a title and a description);
3. the four windows of the park are in victoria-park/optimise-landmarks' test set;
4. every code exercise ships ≥ 8 mutants and ≥ 3 variants, each saying what it is (that each
   mutant is rejected and each variant accepted in the real sandbox is checked once, by
   ``test_bundled_course.py::test_exercise_is_sound``).
"""

from __future__ import annotations

import importlib.util
import itertools
import math
import re
import xml.etree.ElementTree as ET
from collections import Counter
from functools import lru_cache
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import splu, spsolve
from scipy.stats import chi2 as chi2_dist

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root

ROOT = Path(__file__).resolve().parents[2]
FOLDER = ROOT / "exercises" / "victoria-park"
CHAPTER = (ROOT / "chapters" / "24-victoria-park.md").read_text(encoding="utf-8")
PROSE = " ".join(CHAPTER.split())
TEXT = (FOLDER / "data" / "victoria_park.txt").read_text(encoding="utf-8")
COURSE = load_course(bundled_course_root())


def _load(path: Path, name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ref = _load(FOLDER / "reference.py", "_ref_victoria_park")


def _in_prose(text: str) -> None:
    assert text in PROSE, text


def _yaml(slug: str) -> str:
    return " ".join((FOLDER / f"{slug}.yaml").read_text(encoding="utf-8").split())


# --- 1. an independent reader and optimiser -------------------------------------------------


class Park:
    """The lines as arrays: odometry (from, to, z, covariance) and sightings (pose, tree, z,
    covariance), poses and trees indexed by increasing id."""

    def __init__(self, text: str) -> None:
        odo = [ln.split() for ln in text.splitlines() if ln.startswith("ODOMETRY")]
        obs = [ln.split() for ln in text.splitlines() if ln.startswith("LANDMARK")]
        o = np.array([[float(v) for v in f[1:]] for f in odo])
        s = np.array([[float(v) for v in f[1:]] for f in obs])
        self.pose_ids = np.unique(np.concatenate([o[:, 0], o[:, 1], s[:, 0]])).astype(int)
        self.tree_ids = np.unique(s[:, 1]).astype(int)
        self.oi = np.searchsorted(self.pose_ids, o[:, 0].astype(int))
        self.oj = np.searchsorted(self.pose_ids, o[:, 1].astype(int))
        self.li = np.searchsorted(self.pose_ids, s[:, 0].astype(int))
        self.ll = np.searchsorted(self.tree_ids, s[:, 1].astype(int))
        self.oz, self.lz = o[:, 2:5], s[:, 2:4]
        u, w = o[:, 5:], s[:, 4:]
        self.ocov = np.stack([u[:, [0, 1, 2]], u[:, [1, 3, 4]], u[:, [2, 4, 5]]], axis=1)
        self.lcov = np.stack([w[:, [0, 1]], w[:, [1, 2]]], axis=1)
        self.oinf, self.linf = np.linalg.inv(self.ocov), np.linalg.inv(self.lcov)
        self.n, self.m = len(self.pose_ids), len(self.tree_ids)

    def head(self, count: int) -> Park:
        """The first ``count`` poses, their odometry and sightings, trees renumbered."""
        out = object.__new__(Park)
        ko, kl = self.oj < count, self.li < count
        used = np.unique(self.ll[kl])
        out.pose_ids, out.tree_ids = self.pose_ids[:count], self.tree_ids[used]
        out.oi, out.oj, out.oz = self.oi[ko], self.oj[ko], self.oz[ko]
        out.ocov, out.oinf = self.ocov[ko], self.oinf[ko]
        out.li, out.ll = self.li[kl], np.searchsorted(used, self.ll[kl])
        out.lz, out.lcov, out.linf = self.lz[kl], self.lcov[kl], self.linf[kl]
        out.n, out.m = count, len(used)
        return out


def _mats(p: np.ndarray) -> np.ndarray:
    c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
    m = np.zeros((len(p), 3, 3))
    m[:, 0, 0], m[:, 0, 1], m[:, 1, 0], m[:, 1, 1] = c, -s, s, c
    m[:, 0, 2], m[:, 1, 2], m[:, 2, 2] = p[:, 0], p[:, 1], 1.0
    return m


def _inv(m: np.ndarray) -> np.ndarray:
    out = np.zeros_like(m)
    rt = np.transpose(m[:, :2, :2], (0, 2, 1))
    out[:, :2, :2] = rt
    out[:, :2, 2] = -np.einsum("kij,kj->ki", rt, m[:, :2, 2])
    out[:, 2, 2] = 1.0
    return out


def _odo_err(xi: np.ndarray, xj: np.ndarray, z: np.ndarray) -> np.ndarray:
    m = _inv(_mats(z)) @ _inv(_mats(xi)) @ _mats(xj)
    return np.stack([m[:, 0, 2], m[:, 1, 2], np.arctan2(m[:, 1, 0], m[:, 0, 0])], axis=1)


def _xy_err(x: np.ndarray, tree: np.ndarray, z: np.ndarray) -> np.ndarray:
    point = np.concatenate([tree, np.ones((len(tree), 1))], axis=1)
    return np.einsum("kij,kj->ki", _inv(_mats(x)), point)[:, :2] - z


def _rb_err(x: np.ndarray, tree: np.ndarray, z: np.ndarray) -> np.ndarray:
    """GTSAM's reading: (bearing, range) predicted minus measured, bearing wrapped."""
    local = _xy_err(x, tree, np.zeros_like(z))
    b = np.arctan2(local[:, 1], local[:, 0]) - np.arctan2(z[:, 1], z[:, 0])
    b = np.arctan2(np.sin(b), np.cos(b))
    return np.stack([b, np.hypot(local[:, 0], local[:, 1]) - np.hypot(z[:, 0], z[:, 1])], axis=1)


def _numeric(f: Any, a: np.ndarray, b: np.ndarray, z: np.ndarray, wrap: int | None) -> np.ndarray:
    """Central differences (step 1e-6) of ``f(a, b, z)`` by the columns of ``a`` then ``b``."""
    cols = []
    for which, base in ((0, a), (1, b)):
        for c in range(base.shape[1]):
            d = np.zeros(base.shape[1])
            d[c] = 1e-6
            hi = f(a + d, b, z) if which == 0 else f(a, b + d, z)
            lo = f(a - d, b, z) if which == 0 else f(a, b - d, z)
            diff = hi - lo
            if wrap is not None:
                diff[:, wrap] = np.arctan2(np.sin(diff[:, wrap]), np.cos(diff[:, wrap]))
            cols.append(diff / 2e-6)
    return np.stack(cols, axis=2)


def _chi2s(p: Park, x: np.ndarray, t: np.ndarray, model: str = "xy") -> tuple[Any, Any]:
    eo = _odo_err(x[p.oi], x[p.oj], p.oz)
    if model == "xy":
        el, om = _xy_err(x[p.li], t[p.ll], p.lz), p.linf
    else:
        el, c11 = _rb_err(x[p.li], t[p.ll], p.lz), p.lcov[:, 0, 0]
        om = np.zeros((len(el), 2, 2))
        om[:, 0, 0], om[:, 1, 1] = 10 / c11, 1 / c11
    return np.einsum("ka,kab,kb->k", eo, p.oinf, eo), np.einsum("ka,kab,kb->k", el, om, el)


def _system(p: Park, x: np.ndarray, t: np.ndarray, model: str = "xy") -> tuple[Any, np.ndarray]:
    """``H`` (sparse CSC, pose 0 removed) and ``b`` with central-difference Jacobians."""
    xi, xj, pl, tl = x[p.oi], x[p.oj], x[p.li], t[p.ll]
    eo = _odo_err(xi, xj, p.oz)
    jo = _numeric(_odo_err, xi, xj, p.oz, 2)
    if model == "xy":
        el, jl, om = _xy_err(pl, tl, p.lz), _numeric(_xy_err, pl, tl, p.lz, None), p.linf
    else:
        el, jl = _rb_err(pl, tl, p.lz), _numeric(_rb_err, pl, tl, p.lz, 0)
        om = np.zeros((len(el), 2, 2))
        om[:, 0, 0], om[:, 1, 1] = 10 / p.lcov[:, 0, 0], 1 / p.lcov[:, 0, 0]
    size = 3 * p.n + 2 * p.m
    g = np.zeros(size)
    rows, cols, vals = [], [], []
    io = np.concatenate([3 * p.oi[:, None] + np.arange(3), 3 * p.oj[:, None] + np.arange(3)], 1)
    il = np.concatenate(
        [3 * p.li[:, None] + np.arange(3), 3 * p.n + 2 * p.ll[:, None] + np.arange(2)], 1
    )
    for idx, jac, info, e in ((io, jo, p.oinf, eo), (il, jl, om, el)):
        jto = np.einsum("kai,kab->kib", jac, info)
        np.add.at(g, idx, np.einsum("kib,kb->ki", jto, e))
        w = idx.shape[1]
        rows.append(np.repeat(idx, w, 1).ravel())
        cols.append(np.tile(idx, (1, w)).ravel())
        vals.append(np.einsum("kib,kbj->kij", jto, jac).ravel())
    h = coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size)
    ).tocsc()[3:, 3:]
    return h, g[3:]


def _step(
    p: Park, x: np.ndarray, t: np.ndarray, model: str = "xy"
) -> tuple[np.ndarray, np.ndarray, float]:
    h, g = _system(p, x, t, model)
    d = spsolve(h, -g)
    y = x.copy()
    y[1:] += d[: 3 * (p.n - 1)].reshape(-1, 3)
    y[:, 2] = np.arctan2(np.sin(y[:, 2]), np.cos(y[:, 2]))
    return y, t + d[3 * (p.n - 1) :].reshape(-1, 2), float(np.max(np.abs(d)))


def _dead_reckoning(p: Park, x: np.ndarray, start: int = 0) -> None:
    """Chain the poses after ``start`` by odometry, in place: ``X_b = X_a Z``."""
    for a, b, z in zip(p.oi, p.oj, p.oz, strict=True):
        if b > start:
            m = _mats(x[a : a + 1])[0] @ _mats(z[None])[0]
            x[b] = (m[0, 2], m[1, 2], math.atan2(m[1, 0], m[0, 0]))


def _first_sightings(p: Park, x: np.ndarray) -> np.ndarray:
    first = np.unique(p.ll, return_index=True)[1]
    point = np.concatenate([p.lz[first], np.ones((len(first), 1))], axis=1)
    return np.einsum("kij,kj->ki", _mats(x[p.li[first]]), point)[:, :2]


PARK = Park(TEXT)


@lru_cache(maxsize=1)
def _initial() -> tuple[np.ndarray, np.ndarray]:
    x = np.zeros((PARK.n, 3))
    _dead_reckoning(PARK, x)
    return x, _first_sightings(PARK, x)


@lru_cache(maxsize=1)
def _optimum() -> tuple[np.ndarray, np.ndarray]:
    """The reference's optimum of the whole park (its batches), checked below by this file's
    own Gauss-Newton."""
    x, t = ref.optimum()
    return np.array(x), np.array(t)


def test_the_reference_optimum_is_a_minimum() -> None:
    """This file's own errors and central-difference Jacobians: one more Gauss-Newton step
    from the reference's optimum moves nothing by more than a millimetre (the Jacobians'
    rounding alone shifts the fixed point of this ill-conditioned chain by a fraction of one),
    and lowers χ² by less than 10⁻⁶ of itself."""
    x, t = _optimum()
    before = float(sum(v.sum() for v in _chi2s(PARK, x, t)))
    y, s, largest = _step(PARK, x, t)
    after = float(sum(v.sum() for v in _chi2s(PARK, y, s)))
    assert largest < 1e-3
    assert before - after < 1e-6 * before
    assert before == pytest.approx(ref.vp.chi2(x, t, ref.park()), rel=1e-10)


def test_the_file_counted() -> None:
    assert (PARK.n, PARK.m, len(PARK.oz), len(PARK.lz)) == (6969, 151, 6968, 3640)
    ids = sorted([*PARK.pose_ids.tolist(), *PARK.tree_ids.tolist()])
    assert ids == list(range(7120))  # one numbering, every id used once
    assert ref.landmark_count() == 151 and ref.mistake_count_edges_as_poses() == 152
    per_pose = Counter(PARK.li.tolist())
    assert len(per_pose) == 3331 and max(per_pose.values()) == 2
    _in_prose("the 3640 sightings are made from 3331 of the poses, never more than two trees")
    length = float(np.sum(np.hypot(PARK.oz[:, 0], PARK.oz[:, 1])))
    assert round(length / 1000, 2) == 4.03 and round(length / len(PARK.oz), 2) == 0.58
    _in_prose("add up to a drive of 4.03 km, 0.58 m per step on average")
    r = np.hypot(PARK.lz[:, 0], PARK.lz[:, 1])
    bearing = np.degrees(np.abs(np.arctan2(PARK.lz[:, 1], PARK.lz[:, 0])))
    assert (round(r.min(), 1), round(r.max(), 1), round(bearing.max())) == (4.6, 20.7, 76)
    _in_prose("Trees are seen between 4.6 m and 20.7 m away and within 76° of straight ahead")
    per_tree = Counter(PARK.ll.tolist())
    once = sum(1 for v in per_tree.values() if v == 1)
    assert (once, max(per_tree.values()), np.median(list(per_tree.values()))) == (28, 171, 13)
    _in_prose("28 trees are seen a single time. The busiest is seen 171 times")
    _in_prose("half the trees are seen at most 13 times")
    assert round(3640 / 151, 1) == 24.1
    assert "about 24 times each" in _yaml("landmark-count")


def test_a_tree_takes_the_next_free_number() -> None:
    first = np.unique(PARK.ll, return_index=True)[1]
    seen_from = PARK.pose_ids[PARK.li[first]]
    assert np.array_equal(PARK.tree_ids, seen_from + 1)
    lines = TEXT.splitlines()
    assert lines[3:6] == [
        ln
        for ln in CHAPTER.splitlines()
        if ln.startswith(("ODOMETRY 3 4", "LANDMARK 4 5", "ODOMETRY 4 6"))
    ]


def test_the_covariances_of_the_file() -> None:
    assert np.all(PARK.ocov == np.diag([1e-4, 4e-6, 4e-6]))
    assert np.all(PARK.lcov == 0.4 * np.eye(2))
    sx, sy, st = np.sqrt([1e-4, 4e-6, 4e-6])
    assert (round(sx, 3), round(sy, 3), round(st, 3), round(math.degrees(st), 2)) == (
        0.01,
        0.002,
        0.002,
        0.11,
    )
    _in_prose("1 cm along the motion, 2 mm across it and 2 mrad (0.11°) of heading, per step")
    _in_prose("$0.4\\,I$ m², a standard deviation of 0.63 m in every direction")
    assert round(math.sqrt(0.4), 2) == 0.63


def test_gtsams_reading() -> None:
    sb, sr = math.sqrt(0.4 / 10), math.sqrt(0.4)
    assert (round(sb, 3), round(math.degrees(sb), 1), round(10 * sb, 1), round(20 * sb, 1)) == (
        0.2,
        11.5,
        2.0,
        4.0,
    )
    assert round(sr / 10, 3) == 0.063
    _in_prose(
        "0.63 m of range noise and 0.2 rad, 11.5°, of bearing noise: 2 m sideways at 10 m, "
        "4 m at 20 m"
    )
    _in_prose("a bearing noise of $0.063$ rad")
    assert ref.gtsam_sideways(c11=0.4, r=15) == pytest.approx(15 * sb)
    assert math.sqrt(10) == pytest.approx(3.16, abs=0.005)
    assert "11°" in _yaml("gtsam-sideways") and "2 m at 10 m" in _yaml("gtsam-sideways")


def test_the_xy_error_canonical_line_is_real() -> None:
    """Pose 2644 and tree 346 at the optimum, rounded as in the exercise; the line's z."""
    x, t = _optimum()
    i = int(np.searchsorted(PARK.pose_ids, 2644))
    k = int(np.searchsorted(PARK.tree_ids, 346))
    assert np.allclose(x[i, :2], (-30.0, -13.38), atol=0.005) and abs(x[i, 2] - 0.339) < 5e-4
    assert np.allclose(t[k], (-22.56, -3.19), atol=0.005)
    assert "LANDMARK 2644 346 10.3988 7.00428 0.4 0 0.4" in TEXT
    e = ref.xy_error(xr=-30.0, yr=-13.38, tr=0.339, lx=-22.56, ly=-3.19, zx=10.3988, zy=7.00428)
    c, s = math.cos(0.339), math.sin(0.339)
    assert e == pytest.approx([c * 7.44 + s * 10.19 - 10.3988, -s * 7.44 + c * 10.19 - 7.00428])


def test_unknowns_degrees_of_freedom_and_blocks() -> None:
    assert 3 * PARK.n + 2 * PARK.m == 21209
    _in_prose("$3 \\cdot 6969 + 2 \\cdot 151 = 21\\,209$ numbers, 21 206 once pose 0 is fixed")
    dof = 3 * len(PARK.oz) + 2 * len(PARK.lz) - 3 * (PARK.n - 1) - 2 * PARK.m
    assert dof == ref.degrees_of_freedom() == 6978 == 2 * (3640 - 151)
    assert ref.mistake_dof_gauge_ignored() == 6975
    # the block pattern of H, counted from a sparse matrix of ones
    var = np.concatenate([PARK.oi, PARK.oj, PARK.li, PARK.n + PARK.ll])
    other = np.concatenate([PARK.oj, PARK.oi, PARK.n + PARK.ll, PARK.li])
    size = PARK.n + PARK.m
    diag = np.arange(size)
    pattern = coo_matrix(
        (np.ones(len(var) + size), (np.r_[var, diag], np.r_[other, diag])), shape=(size, size)
    ).tocsr()
    assert pattern.nnz == ref.nonzero_blocks() == 28336
    assert round(size**2 / 1e6, 1) == 50.7
    _in_prose("about 28 000 of the $7120^2 \\approx 50.7$ million blocks are non-zero")
    assert round(21209**2 * 8 / 1e9, 1) == 3.6
    _in_prose("$21\\,209 \\times 21\\,209$ matrix of doubles would take 3.6 GB")
    assert round(100 * 28336 / size**2, 2) == 0.06
    assert "about 0.06 %" in _yaml("nonzero-blocks")


def test_dead_reckoning_ends_far_away() -> None:
    x0, _ = _initial()
    x, _ = _optimum()
    end = float(np.hypot(*(x0[-1, :2] - x[-1, :2])))
    turn = float(np.angle(np.exp(1j * (x0[-1, 2] - x[-1, 2]))))
    assert (round(end), round(abs(turn), 2), round(math.degrees(abs(turn)))) == (202, 1.23, 70)
    _in_prose(
        "the odometry ends 202 m from where the optimum puts the car, with its heading "
        "1.23 rad (70°) off"
    )


@pytest.mark.slow
def test_gauss_newton_from_dead_reckoning_is_stuck() -> None:
    x, t = _initial()
    history = [float(sum(v.sum() for v in _chi2s(PARK, x, t)))]
    for _ in range(20):
        x, t, largest = _step(PARK, x, t)
        history.append(float(sum(v.sum() for v in _chi2s(PARK, x, t))))
    assert round(history[0], -7) == 1.3e8 and max(history[:5]) > 1e9 > max(history[:4])
    assert round(history[20], -4) == 830e3 and largest > 5
    assert round(history[20] / 6978, -1) == 120
    _in_prose("$\\chi^2$ starts at $1.3 \\cdot 10^8$ and climbs past $10^9$ in four steps")
    _in_prose(
        "After twenty steps it is still about 830 000, 120 times the degrees of freedom, and "
        "each step still moves poses by metres"
    )
    stuck = _yaml("stuck")
    assert "about 830 000, and each step still moves poses by metres" in stuck
    assert "about 120" in stuck  # "multiply every covariance by about 120"


def test_the_batches() -> None:
    """The reference's four batches (its procedure); the χ² at the end by this file's code."""
    stages = ref.batches()[2]
    assert [st.poses for st in stages] == [2000, 4000, 6000, 6969]
    assert min(st.steps for st in stages) == 10 and max(st.steps for st in stages) == 14
    _in_prose("Each of the four batches converges in 10 to 14 steps")
    x, t = _optimum()
    total = float(sum(v.sum() for v in _chi2s(PARK, x, t)))
    assert round(total, 1) == 6184.1 and stages[-1].dof == 6978
    _in_prose("the last ends at $\\chi^2 = 6184.1$, with 6978 degrees of freedom")


# --- EKF-SLAM, independently ------------------------------------------------------------------


@lru_cache(maxsize=1)
def _ekf() -> tuple[np.ndarray, np.ndarray, list[int], np.ndarray]:
    """The lines in file order: mean, covariance, trees in state order, NIS of each update."""
    mean, p = np.zeros(3), np.zeros((3, 3))
    where: dict[str, int] = {}
    order: list[int] = []
    nis = []
    for line in TEXT.splitlines():
        f = line.split()
        th = mean[2]
        c, s = math.cos(th), math.sin(th)
        rot = np.array([[c, -s], [s, c]])
        if f[0] == "ODOMETRY":
            z = np.array([float(v) for v in f[3:6]])
            c11, c12, c13, c22, c23, c33 = (float(v) for v in f[6:12])
            motion = np.array([[c11, c12, c13], [c12, c22, c23], [c13, c23, c33]])
            g = np.eye(3)
            g[:2, 2] = rot @ np.array([-z[1], z[0]])
            v = np.eye(3)
            v[:2, :2] = rot
            mean[:2] += rot @ z[:2]
            mean[2] = math.atan2(math.sin(th + z[2]), math.cos(th + z[2]))
            p[:3, :] = g @ p[:3, :]
            p[:, :3] = p[:, :3] @ g.T
            p[:3, :3] += v @ motion @ v.T
            continue
        z = np.array([float(f[3]), float(f[4])])
        r = np.array([[float(f[5]), float(f[6])], [float(f[6]), float(f[7])]])
        if f[2] not in where:  # new tree: l = t + R z, blocks by G_r = [I, R (−z_y, z_x)], G_z = R
            n = len(mean)
            gr = np.zeros((2, 3))
            gr[:, :2] = np.eye(2)
            gr[:, 2] = rot @ np.array([-z[1], z[0]])
            big = np.zeros((n + 2, n + 2))
            big[:n, :n] = p
            big[n:, :n] = gr @ p[:3, :]
            big[:n, n:] = big[n:, :n].T
            big[n:, n:] = gr @ p[:3, :3] @ gr.T + rot @ r @ rot.T
            mean, p = np.concatenate([mean, mean[:2] + rot @ z]), big
            where[f[2]] = n
            order.append(int(f[2]))
            continue
        k = where[f[2]]
        d = mean[k : k + 2] - mean[:2]
        h = rot.T @ d
        jac = np.zeros((2, len(mean)))
        jac[:, :2] = -rot.T
        jac[:, 2] = [h[1], -h[0]]
        jac[:, k : k + 2] = rot.T
        ph = p @ jac.T
        sm = jac @ ph + r
        nu = z - h
        gain = np.linalg.solve(sm, ph.T).T
        nis.append(float(nu @ np.linalg.solve(sm, nu)))
        mean = mean + gain @ nu
        mean[2] = math.atan2(math.sin(mean[2]), math.cos(mean[2]))
        p = p - gain @ sm @ gain.T
        p = (p + p.T) / 2
    return mean, p, order, np.array(nis)


@pytest.mark.slow
def test_ekf_slam_on_the_park() -> None:
    mean, p, order, nis = _ekf()
    run = ref.vp.ekf_slam(ref.park())
    assert np.allclose(run.mean, mean, atol=1e-6) and np.allclose(run.nis, nis, atol=1e-6)
    assert len(mean) == 305 and len(nis) == 3489 == 3640 - 151
    _in_prose("The state grows to 305 entries")
    _in_prose(
        "Over the 3489 updates (the 3640 sightings minus the 151 first ones) the NIS averages 1.82"
    )
    assert round(nis.mean(), 2) == 1.82
    gate = chi2_dist.ppf(0.95, 2)
    assert round(100 * np.mean(nis > gate), 1) == 7.1
    _in_prose("7.1 % of the updates fall beyond the 95 % gate")
    assert round(nis[:1000].mean(), 2) == 2.33 and len(nis[3000:]) == 489
    assert round(nis[3000:].mean(), 2) == 1.04
    _in_prose("from a mean of 2.33 over the first thousand updates to 1.04 over the last 489")
    _, t = _optimum()
    idx = np.searchsorted(PARK.tree_ids, order)
    filtered = mean[3:].reshape(-1, 2)
    gap = np.hypot(*(filtered - t[idx]).T)
    assert (round(gap.mean(), 1), round(gap.max(), 1)) == (13.7, 38.7)
    _in_prose("the filter's trees are off by 13.7 m on average and by up to 38.7 m")
    outside = 0
    for j in range(len(idx)):
        d = filtered[j] - t[idx[j]]
        block = p[3 + 2 * j : 5 + 2 * j, 3 + 2 * j : 5 + 2 * j]
        outside += int(d @ np.linalg.solve(block, d) > gate)
    assert outside == 150
    _in_prose("150 of the 151 lie outside the 95 % ellipse the filter itself draws around them")


# --- is the model right? ----------------------------------------------------------------------


def test_chi2_band_and_groups() -> None:
    x, t = _optimum()
    co, cl = _chi2s(PARK, x, t)
    assert (round(co.sum(), 1), round(cl.sum(), 1)) == (4441.2, 1742.9)
    lo, hi = chi2_dist.ppf([0.025, 0.975], 6978)
    assert (round(lo), round(hi)) == (6748, 7211)
    _in_prose("whose two-sided 95 % band is $[6748, 7211]$")
    chi_odo, chi_obs, r_odo, r_obs = ref.group_chi2()
    assert chi_odo == pytest.approx(co.sum(), rel=1e-6) and chi_obs == pytest.approx(
        cl.sum(), rel=1e-6
    )
    assert (round(r_odo, 1), round(r_obs, 1)) == (133.0, 6845.0)
    assert r_odo + r_obs == pytest.approx(6978, abs=1e-6)
    _in_prose("the odometry lines have a redundancy of 133.0, and the sightings 6845.0")
    _in_prose(
        "The odometry lines contribute $\\chi^2 = 4441.2$, 33 times their 133.0. "
        "The sightings contribute 1742.9, a quarter of their 6845.0"
    )
    assert round(co.sum() / r_odo) == 33 and round(math.sqrt(co.sum() / r_odo), 1) == 5.8
    assert round(cl.sum() / r_obs, 2) == 0.25 and round(r_obs / cl.sum()) == 4
    _in_prose("about $\\sqrt{33} \\approx 5.8$ times too small")
    assert (round(cl.mean(), 2), round(r_obs / 3640, 2)) == (0.48, 1.88)
    _in_prose(
        "Per line, their $e^T\\Omega e$ averages 0.48 at the optimum, where the redundancy "
        "leaves room for 1.88 on average"
    )
    # the exercise's canonical numbers are these, rounded
    text = (FOLDER / "odometry-factor.yaml").read_text(encoding="utf-8")
    assert f"canonical: {round(co.sum(), 2)}" in text and f"canonical: {round(r_odo, 2)}" in text
    assert round(100 * (7280 - r_obs) / 7280) == 6
    _in_prose("only about 6 % of the error components are absorbed")


@pytest.mark.slow
def test_redundancy_by_a_stochastic_trace() -> None:
    """Hutchinson's estimate of the sightings' leverage ``tr(W H⁻¹ Wᵀ)``, W the whitened
    sighting Jacobians, with 120 random sign vectors: within five standard errors."""
    x, t = _optimum()
    h, _ = _system(PARK, x, t)
    lu = splu(h.tocsc())
    pl, tl = x[PARK.li], t[PARK.ll]
    jac = _numeric(_xy_err, pl, tl, PARK.lz, None)
    root = np.linalg.cholesky(PARK.linf)  # Ω = L Lᵀ, whitened rows Lᵀ J
    w = np.einsum("kba,kbj->kaj", root, jac)
    idx = (
        np.concatenate(
            [3 * PARK.li[:, None] + np.arange(3), 3 * PARK.n + 2 * PARK.ll[:, None] + np.arange(2)],
            1,
        )
        - 3
    )
    rows = np.repeat(np.arange(2 * len(w)).reshape(-1, 2)[:, :, None], 5, axis=2)
    cols = np.repeat(idx[:, None, :], 2, axis=1)
    keep = cols >= 0
    wm = coo_matrix((w[keep], (rows[keep], cols[keep])), shape=(2 * len(w), h.shape[0])).tocsr()
    rng = np.random.default_rng(2013)
    estimates = []
    for _ in range(120):
        v = rng.choice([-1.0, 1.0], size=wm.shape[0])
        u = wm.T @ v
        estimates.append(float(u @ lu.solve(u)))
    mean, se = float(np.mean(estimates)), float(np.std(estimates) / math.sqrt(len(estimates)))
    _, _, _, r_obs = ref.group_chi2()
    assert abs((7280 - mean) - r_obs) < 5 * se and se < 5


def test_the_sightings_residuals() -> None:
    x, t = _optimum()
    e = _xy_err(x[PARK.li], t[PARK.ll], PARK.lz)
    r = np.hypot(PARK.lz[:, 0], PARK.lz[:, 1])
    u = PARK.lz / r[:, None]
    along = np.sum(e * u, axis=1)
    across = e[:, 1] * u[:, 0] - e[:, 0] * u[:, 1]
    bins = (4, 8, 10, 12, 14, 16, 18, 21)
    a_rms, c_rms = [], []
    for lo, hi in itertools.pairwise(bins):
        k = (r >= lo) & (r < hi)
        a_rms.append(math.sqrt(np.mean(along[k] ** 2)))
        c_rms.append(math.sqrt(np.mean(across[k] ** 2)))
    assert (round(min(a_rms), 2), round(max(a_rms), 2)) == (0.17, 0.41)
    assert (round(min(c_rms), 2), round(max(c_rms), 2)) == (0.24, 0.46)
    _in_prose(
        "a root-mean-square of 0.17 to 0.41 m along the line of sight and 0.24 to 0.46 m across it"
    )
    from slamcourse.plots import ch_victoria_park as plots

    profile = plots.residual_profile()
    assert np.allclose([p[2] for p in profile], a_rms) and np.allclose(
        [p[3] for p in profile], c_rms
    )
    # across the line of sight: up to 12 m, then beyond 18 m
    assert (round(min(c_rms[:3]), 2), round(max(c_rms[:3]), 2), round(c_rms[-1], 2)) == (
        0.24,
        0.36,
        0.46,
    )
    _in_prose("0.24 to 0.36 m for trees up to 12 m away, 0.46 m for those beyond 18 m")


@pytest.mark.slow
def test_gtsams_reading_moves_the_trees() -> None:
    x, t = _optimum()
    y, s = x.copy(), t.copy()
    for _ in range(40):  # to within the rounding of the central differences (see above)
        y, s, largest = _step(PARK, y, s, "gtsam")
        if largest < 1e-3:
            break
    assert largest < 1e-3
    shift = np.hypot(*(s - t).T)
    assert (round(shift.mean(), 1), round(shift.max(), 1)) == (2.2, 4.3)
    _in_prose(
        "the trees move by 2.2 m on average, and up to 4.3 m, from where the x-y model puts them"
    )


def test_the_outliers() -> None:
    x, t = _optimum()
    _, cl = _chi2s(PARK, x, t)
    gate = chi2_dist.ppf(0.999, 2)
    worst = np.argsort(cl)[::-1][:9]
    assert round(gate, 1) == 13.8 and int(np.sum(cl > gate)) == 9
    assert round(3640 * 0.001, 1) == 3.6
    _in_prose(
        "Nine sightings have $e^T\\Omega e$ above 13.8, the 99.9 % point of $\\chi^2_2$. "
        "Of 3640 lines a correct model would put 3.6 there"
    )
    e = _xy_err(x[PARK.li[worst[:1]]], t[PARK.ll[worst[:1]]], PARK.lz[worst[:1]])
    assert round(cl[worst[0]]) == 259 and round(float(np.hypot(*e[0]))) == 10
    _in_prose("The worst is 259, a 10 m miss")
    trees = PARK.tree_ids[PARK.ll[worst]]
    poses = PARK.pose_ids[PARK.li[worst]][trees == 4983]
    assert int(np.sum(trees == 4983)) == 5 and trees[0] == 4983
    assert (poses.min(), poses.max()) == (5005, 5018)
    _in_prose(
        "Five of the nine, the worst among them, are sightings of tree 4983 from poses 5005 to 5018"
    )


# --- the prose's other claims -----------------------------------------------------------------


def test_sparsity_figure_counts() -> None:
    from slamcourse.plots import ch_victoria_park as plots

    n, m, _ = plots.sparsity_cells()
    assert (n, m) == (40, 5)
    assert "first 40 poses of the drive and the five trees they see" in PROSE


def test_the_odometry_chain_has_no_redundancy() -> None:
    """A chain alone: as many error components as free unknowns, fitted exactly."""
    sub = PARK.head(50)
    assert 3 * len(sub.oz) == 3 * (sub.n - 1)
    x = np.zeros((sub.n, 3))
    _dead_reckoning(sub, x)
    eo = _odo_err(x[sub.oi], x[sub.oj], sub.oz)
    assert np.max(np.abs(eo)) < 1e-12


# --- 2. figures and pictures ------------------------------------------------------------------


def _svg_ok(svg: str) -> None:
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    assert root.find(f"{ns}title") is not None
    desc = root.find(f"{ns}desc")
    assert desc is not None and (desc.text or "").strip()


def test_figures_and_pictures_draw() -> None:
    from slamcourse.plots import registry

    placed = re.findall(r"```\{figure\} (\S+)", CHAPTER)
    assert placed == [
        "victoria-park/sparsity",
        "victoria-park/park",
        "victoria-park/ekf-vs-graph",
        "victoria-park/residuals",
    ]
    for figure in placed:
        svg = registry.figure_svg(figure)
        assert svg is not None
        _svg_ok(svg)
    for exercise in (
        "victoria-park/landmark-jacobian",
        "victoria-park/optimise-landmarks",
        "victoria-park/nonzero-blocks",
    ):
        svg = registry.plot_for(exercise, [], {}, solved=False)
        assert svg is not None
        _svg_ok(svg)
    params = {
        "xr": -30.0,
        "yr": -13.38,
        "tr": 0.339,
        "dx": 7.44,
        "dy": 10.19,
        "lx": -22.56,
        "ly": -3.19,
        "zx": 10.3988,
        "zy": 7.00428,
    }
    for exercise, p in (
        ("victoria-park/xy-error", params),
        ("victoria-park/gtsam-sideways", {"c11": 0.4, "r": 15}),
    ):
        svg = registry.plot_for(exercise, [], p, solved=True)
        assert svg is not None
        _svg_ok(svg)


# --- 3. the real windows are graded ------------------------------------------------------------


@lru_cache(maxsize=2)
def _tests(exercise: str) -> Any:
    from slamcourse.grading import testset

    return testset.build(COURSE.exercise(exercise))


def test_the_test_set_holds_the_windows() -> None:
    texts = [case.kwargs["text"] for case in _tests("victoria-park/optimise-landmarks").cases]
    for first, _ in ref.WINDOWS:
        assert ref.park_window(first) in texts
        assert ref.park_window(first).count("ODOMETRY") == ref.WINDOW_POSES - 1 == 99
    spec = COURSE.exercise("victoria-park/optimise-landmarks")
    assert all(ex["text"].count("ODOMETRY") <= 20 for ex in spec.options.examples)


# --- 4. enough mutants and variants -----------------------------------------------------------

SLUGS = ("landmark-jacobian", "optimise-landmarks")


def test_enough_mutants_and_variants() -> None:
    for slug in SLUGS:
        mutants = sorted((FOLDER / "mutants" / slug).glob("*.py"))
        variants = sorted((FOLDER / "variants" / slug).glob("*.py"))
        assert len(mutants) >= 8 and len(variants) >= 3
        assert all(p.read_text(encoding="utf-8").startswith("# mistake: ") for p in mutants)
        assert all(p.read_text(encoding="utf-8").startswith("# method: ") for p in variants)
