"""Planar meshes: (#V, 2) arrays deform in their plane (rotations about z) and equal the solver in space
on the same mesh embedded at z = 0 where no cell is squeezed through a reflection."""
import numpy as np
import pytest

import iarap

METHODS = ["iarap", "spokes-rims", "arap"]


def grid(n):
    """(n + 1)^2 vertices on [0, 1]^2, each square split by the same diagonal (Delaunay)."""
    x, y = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    V = np.column_stack([x.ravel(), y.ravel()])
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            F += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return V, np.array(F)


def bend(V, degrees=10.0):
    """Left column fixed, right column turned about the centre and shifted: no cell reflects."""
    fixed = np.flatnonzero((V[:, 0] < 1e-9) | (V[:, 0] > 1 - 1e-9))
    a = np.radians(degrees)
    R = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    targets = V[fixed].copy()
    right = targets[:, 0] > 0.5
    targets[right] = (targets[right] - 0.5) @ R.T + 0.5 + np.array([0.05, 0.02])
    return fixed, targets


@pytest.mark.parametrize("method", METHODS)
def test_planar_equals_the_solver_in_space(method):
    V, F = grid(8)
    fixed, targets = bend(V)
    planar = iarap.ARAP(V, F, fixed=fixed, method=method)
    U = planar.solve(targets, iterations=25, tolerance=-1)
    assert U.shape == V.shape
    space = iarap.ARAP(np.column_stack([V, np.zeros(len(V))]), F, fixed=fixed, method=method)
    U3 = space.solve(np.column_stack([targets, np.zeros(len(targets))]), iterations=25, tolerance=-1)
    np.testing.assert_array_equal(U3[:, 2], 0.0)
    # Rounding apart (closed-form 2x2 rotations against the 3D Newton fit): measured below 1e-13.
    np.testing.assert_allclose(U, U3[:, :2], rtol=0, atol=1e-12 * np.sqrt(2))
    assert np.abs(U - V).max() > 0.03  # it moved
    assert planar.energy(U) == pytest.approx(space.energy(U3), rel=1e-10)
    assert planar.gradient(U).shape == V.shape


def test_planar_shapes_are_checked():
    V, F = grid(3)
    solver = iarap.ARAP(V, F, fixed=[0, 15])
    with pytest.raises(ValueError, match="targets must be a #fixed x 3 \\(or 2\\)"):
        solver.solve(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="targets row 1 has z"):
        solver.solve(np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 0.5]]))
    space = iarap.ARAP(np.column_stack([V, np.zeros(len(V))]), F, fixed=[0, 15])
    with pytest.raises(ValueError, match="x 3"):
        space.solve(np.zeros((2, 2)))
