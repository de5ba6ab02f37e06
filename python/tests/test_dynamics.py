"""Dynamics and statics (issue 32, items 3-4): iarap.Simulation (implicit Euler of the ARAP energy),
iarap.vertex_masses and ARAP.solve(forces=)."""
import numpy as np
import pytest

import iarap
from conftest import bbox_diagonal


@pytest.fixture(autouse=True)
def single_thread():
    """The bunny's 3485 vertices run faster on one thread (as the CLI's automatic choice below 10,000)."""
    before = iarap.thread_count()
    iarap.set_thread_count(1)
    yield
    iarap.set_thread_count(before)


def bottom_of(V):
    y = V[:, 1]
    return np.flatnonzero(y <= y.min() + 0.1 * (y.max() - y.min()))


def test_masses_partition_the_area(bunny):
    V, F = bunny
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    for method in ("iarap", "arap", "spokes-rims"):
        m = iarap.vertex_masses(V, F, method, density=3.0)
        # Voronoi cells (intrinsic or not) tile the surface: density x area, up to rounding.
        assert m.sum() == pytest.approx(3.0 * area, rel=1e-12)
        assert m.min() > 0


def test_rest_stays_at_rest(bunny):
    V, F = bunny
    bottom = bottom_of(V)
    sim = iarap.Simulation(V, F, bottom, dt=0.05)
    for _ in range(5):
        report = sim.step()
        # At rest every term is stationary (E_ARAP = 0, R = I, x_pred = V): only rounding moves it.
        assert np.abs(sim.positions - V).max() <= 1e-10 * bbox_diagonal(V)
    assert report["step"] == 5 and report["time"] == pytest.approx(0.25)
    assert sim.kinetic_energy <= 1e-20


def test_free_body_conserves_momentum(bunny):
    V, F = bunny
    sim = iarap.Simulation(V, F, dt=0.02)
    rng = np.random.default_rng(3)
    sim.velocities = np.array([0.3, -0.2, 0.1]) + 0.2 * rng.standard_normal(V.shape)
    p0 = sim.momentum
    for _ in range(10):
        sim.step()
        # The rows of L and of the right-hand side sum to 0: each global step keeps sum m (x - x_pred) = 0.
        assert np.linalg.norm(sim.momentum - p0) <= 1e-12 * np.linalg.norm(p0)
    assert sim.elastic_energy > 0  # it wobbles, not only drifts


def test_damped_fall_settles_to_the_statics(bunny):
    V, F = bunny
    bottom = bottom_of(V)
    g = np.array([0.0, -1.0, 0.0])
    density = 0.2  # the bunny (diagonal 0.25) then sags by about 11% of its diagonal
    m = iarap.vertex_masses(V, F, density=density)
    solver = iarap.ARAP(V, F, bottom)
    statics = solver.solve(V[bottom], iterations=1000, tolerance=0, gradient_tolerance=1e-9,
                           forces=m[:, None] * g)
    assert solver.report["potential"] < 0
    sag = np.linalg.norm(statics - V, axis=1).max()
    assert sag > 0.05 * bbox_diagonal(V)
    sim = iarap.Simulation(V, F, bottom, dt=0.1, gravity=g, damping=0.2, density=density)
    for _ in range(150):
        sim.step()
    gap = np.linalg.norm(sim.positions - statics, axis=1).max()
    # 0.8^150 ~ 3e-15 of the first motion is left: the gap is the solvers' tolerances.
    assert gap < 0.01 * sag
    assert gap < 1e-3 * bbox_diagonal(V)
    assert np.allclose(sim.forces, m[:, None] * g, rtol=1e-15, atol=0)


def test_handles_follow_targets(bunny):
    V, F = bunny
    bottom = bottom_of(V)
    sim = iarap.Simulation(V, F, bottom, dt=0.1, damping=0.5)
    targets = V[bottom] + [0.0, 0.0, 0.01]
    sim.step(targets)
    assert np.array_equal(sim.positions[bottom], targets)
    # A handle's velocity is its motion over dt, not damped.
    assert np.allclose(sim.velocities[bottom], [0.0, 0.0, 0.1], rtol=1e-12)


@pytest.mark.parametrize("kwargs, words", [
    (dict(dt=0.0), "dt must be finite and > 0"),
    (dict(dt=-1.0), "dt must be finite and > 0"),
    (dict(dt=float("nan")), "dt must be finite and > 0"),
    (dict(dt=1e-300), "dt = 1e-300 is too small"),  # m / (2 dt^2) overflows: not "soft vertex [0] has weight inf"
    (dict(dt=1e300), "dt = 1e+300 is too large"),
    (dict(dt=0.1, damping=1.0), "damping must be in [0, 1)"),
    (dict(dt=0.1, density=0.0), "density must be finite and > 0"),
    (dict(dt=0.1, gravity=(0.0, float("nan"), 0.0)), "gravity"),
    (dict(dt=0.1, gravity=(0.0, 1.0)), "gravity"),
    (dict(dt=0.1, forces=np.zeros((3, 3))), "forces"),
])
def test_bad_options_are_named(bunny, kwargs, words):
    V, F = bunny
    with pytest.raises(iarap.InputError, match=None) as error:
        iarap.Simulation(V, F, bottom_of(V), **kwargs)
    assert words in str(error.value)


def test_bad_state_is_refused(bunny):
    V, F = bunny
    bottom = bottom_of(V)
    sim = iarap.Simulation(V, F, bottom, dt=0.1)
    with pytest.raises(iarap.InputError, match="velocities"):
        sim.velocities = np.zeros((3, 3))
    with pytest.raises(iarap.InputError, match="targets"):
        sim.step(np.zeros((1, 3)))
    bad = V[bottom].copy()
    bad[0, 0] = np.nan
    with pytest.raises(iarap.InputError):
        sim.step(bad)
    assert sim.steps == 0
    with pytest.raises(iarap.InputError, match="forces"):
        iarap.ARAP(V, F, bottom).solve(V[bottom], forces=np.zeros((2, 3)))
