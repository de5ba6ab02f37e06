"""iarap.register: non-rigid ICP finds a known ARAP deformation of the bunny again from a noisy point cloud
with a hole, closer than the landmarks alone; bad input raises InputError naming the argument."""
import numpy as np
import pytest

import iarap
from conftest import REPO, bbox_diagonal, handle_scene


def sample_surface(V, F, count, noise, seed=46):
    """count points uniform by area on (V, F), Gaussian noise of deviation `noise` per axis; fixed seed."""
    rng = np.random.default_rng(seed)
    area = np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
    f = rng.choice(len(F), count, p=area / area.sum())
    r1, r2 = np.sqrt(rng.random(count)), rng.random(count)
    P = (1 - r1)[:, None] * V[F[f, 0]] + (r1 * (1 - r2))[:, None] * V[F[f, 1]] + (r1 * r2)[:, None] * V[F[f, 2]]
    return P + rng.normal(0.0, noise, P.shape)


@pytest.fixture(scope="module")
def known():
    V, F = iarap.read_mesh(REPO / "data" / "bunny.off")
    fixed, targets = handle_scene(V)
    U = iarap.ARAP(V, F, fixed=fixed).solve(targets)
    return V, F, U, bbox_diagonal(V)


def test_register_finds_a_known_deformation(known):
    V, F, U, diagonal = known
    P = sample_surface(U, F, 12000, 0.001 * diagonal)
    centre = U[np.argmax(U[:, 2])]  # a hole around the front-most point
    P = P[np.linalg.norm(P - centre, axis=1) > 0.08 * diagonal]
    landmarks = np.arange(0, len(V), len(V) // 12)[:12]
    landmarks_only = iarap.ARAP(V, F, fixed=landmarks).solve(U[landmarks])
    fit, report = iarap.register(V, F, P, landmarks=landmarks, landmark_targets=U[landmarks])
    error = np.linalg.norm(fit - U, axis=1).mean() / diagonal
    baseline = np.linalg.norm(landmarks_only - U, axis=1).mean() / diagonal
    assert error < 0.5 * baseline, (error, baseline)
    assert fit.shape == V.shape
    assert report["final_distance"]["mean"] < report["initial_distance"]["mean"]
    assert report["rounds"] and {"closest_ms", "factor_ms", "solve_ms"} <= set(report["rounds"][0])


def test_register_recovers_a_rigid_motion_of_a_mesh_target(known):
    V, F, _, diagonal = known
    R = np.array([[np.cos(0.3), 0.0, np.sin(0.3)], [0.0, 1.0, 0.0], [-np.sin(0.3), 0.0, np.cos(0.3)]])
    t = np.array([0.05, -0.02, 0.01])
    picked = np.array([0, 900, 1800, 2700])
    fit, report = iarap.register(V, F, V @ R.T + t, target_faces=F, landmarks=picked,
                                 landmark_targets=V[picked] @ R.T + t, stages=1, rounds=2)
    np.testing.assert_allclose(report["prealignment"]["R"], R, atol=1e-9)
    np.testing.assert_allclose(report["prealignment"]["t"], t, atol=1e-9)
    assert np.abs(fit - (V @ R.T + t)).max() < 1e-6 * diagonal


def test_register_bad_input(known):
    V, F, _, _ = known
    with pytest.raises(iarap.InputError, match="target_points: the target has no point"):
        iarap.register(V, F, np.zeros((0, 3)))
    with pytest.raises(iarap.InputError, match="target point 1 is not finite"):
        iarap.register(V, F, np.array([[0.0, 0, 0], [np.nan, 0, 0], [0, 1, 0], [1, 1, 1]]))
    with pytest.raises(iarap.InputError, match="need at least 3 points to estimate normals"):
        iarap.register(V, F, np.eye(3)[:2])
    with pytest.raises(iarap.InputError, match="landmarks"):
        iarap.register(V, F, V, landmarks=[len(V)], landmark_targets=[[0.0, 0, 0]])
    with pytest.raises(iarap.InputError, match="give both or neither"):
        iarap.register(V, F, V, landmarks=[0])
    with pytest.raises(iarap.InputError, match="prealign"):
        iarap.register(V, F, V, prealign="affine")
