"""Volumetric ARAP: read_tet_mesh / write_tet_mesh, and iarap.ARAP on (#T, 4) tetrahedra."""
import itertools

import numpy as np
import pytest

import iarap


def tet_bar(nx, ny, nz):
    """A bar of unit cubes, each split into 6 positive tetrahedra around its main diagonal."""
    def vertex(i, j, k):
        return i + (nx + 1) * (j + (ny + 1) * k)
    V = np.array([(i, j, k) for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)], dtype=float)
    T = []
    for k, j, i in itertools.product(range(nz), range(ny), range(nx)):
        for axes in itertools.permutations(range(3)):
            at = [i, j, k]
            corners = [vertex(*at)]
            for a in axes:
                at[a] += 1
                corners.append(vertex(*at))
            T.append(corners)
    T = np.array(T)
    D = V[T[:, 1:]] - V[T[:, :1]]
    negative = np.linalg.det(D) < 0
    T[negative, 2], T[negative, 3] = T[negative, 3], T[negative, 2].copy()
    return V, T


def energy_by_svd(V, T, U):
    """sum_t vol_t |F_t - R_t|^2, R_t the closest rotation to the deformation gradient F_t."""
    Dv = np.transpose(V[T[:, 1:]] - V[T[:, :1]], (0, 2, 1))
    Du = np.transpose(U[T[:, 1:]] - U[T[:, :1]], (0, 2, 1))
    F = Du @ np.linalg.inv(Dv)
    W, _, Vt = np.linalg.svd(F)
    flip = np.linalg.det(W @ Vt) < 0
    W[flip, :, 2] *= -1
    R = W @ Vt
    return float(np.sum(np.abs(np.linalg.det(Dv)) / 6 * np.sum((F - R) ** 2, axis=(1, 2))))


def test_read_write_round_trip(tmp_path):
    V, T = tet_bar(3, 2, 1)
    path = tmp_path / "bar.mesh"
    iarap.write_tet_mesh(path, V, T)
    V2, T2 = iarap.read_tet_mesh(path)
    np.testing.assert_array_equal(V2, V)
    np.testing.assert_array_equal(T2, T)
    assert iarap.tet_boundary_faces(T).shape == (4 * (3 * 2 + 2 * 1 + 3 * 1), 3)
    bad = tmp_path / "bad.mesh"
    bad.write_text("Dimension 3\nVertices 1\n0 0 0 0\nTetrahedra 1\n1 1 2 3 0\nEnd\n")
    with pytest.raises(ValueError, match=r"bad.mesh:5: tetrahedron 0 uses vertex index 2"):
        iarap.read_tet_mesh(bad)


def test_arap_on_tetrahedra_energy_rest_and_twist():
    V, T = tet_bar(6, 2, 2)
    rng = np.random.default_rng(3)
    fixed = np.flatnonzero((V[:, 0] == 0) | (V[:, 0] == 6))
    solver = iarap.ARAP(V, T, fixed)
    U = V + 0.2 * rng.standard_normal(V.shape)
    assert solver.energy(U) == pytest.approx(energy_by_svd(V, T, U), rel=1e-12)
    at_rest = solver.solve(V[fixed], iterations=30, tolerance=-1)
    assert np.abs(at_rest - V).max() <= 1e-12 * np.linalg.norm(V.max(0) - V.min(0))
    a = np.pi / 3  # the x = 6 end turned by 60 degrees about the bar's axis
    targets = V[fixed].copy()
    end = targets[:, 0] == 6
    y, z = targets[end, 1] - 1, targets[end, 2] - 1
    targets[end, 1], targets[end, 2] = 1 + np.cos(a) * y - np.sin(a) * z, 1 + np.sin(a) * y + np.cos(a) * z
    U = solver.solve(targets, iterations=200, tolerance=-1, gradient_tolerance=1e-6)
    assert solver.report["stop_reason"] == "gradient_tolerance"
    assert len(solver.rotations) == len(T)
    volume = lambda X: np.sum(np.linalg.det(X[T[:, 1:]] - X[T[:, :1]])) / 6  # noqa: E731
    assert 0.9 < volume(U) / volume(V) < 1.1


def test_tetrahedra_refuse_surface_methods():
    V, T = tet_bar(1, 1, 1)
    with pytest.raises(ValueError, match="surface energy"):
        iarap.ARAP(V, T, [0], method="arap")


def test_deform_file_reads_a_tet_mesh_as_the_tool_does(cli, tmp_path):
    """deform_file and `iarap deform` read a tetrahedral mesh through the same library job
    (read_deform_scene): the same positions, to the bit, and the boundary faces as F."""
    import json
    import subprocess
    V, T = tet_bar(6, 2, 2)
    path = tmp_path / "bar.mesh"
    iarap.write_tet_mesh(path, V, T)
    x = V[:, 0]
    held = np.flatnonzero(x <= x.min() + 1e-12)
    moved = np.flatnonzero(x >= x.max() - 1e-12)
    constraints = tmp_path / "c.txt"
    constraints.write_text("".join(f"{i} {V[i, 0]} {V[i, 1]} {V[i, 2]}\n" for i in held) +
                           "".join(f"{i} {V[i, 0]} {V[i, 1] + 0.5} {V[i, 2]}\n" for i in moved))
    out = tmp_path / "out.mesh"
    run = subprocess.run([str(cli), "deform", str(path), "--constraints", str(constraints), "--threads", "1",
                          "--out", str(out), "--json", "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    iarap.set_thread_count(1)
    U, F, report = iarap.deform_file(path, constraints=constraints)
    U_tool, T_tool = iarap.read_tet_mesh(out)
    assert np.array_equal(U, U_tool) and np.array_equal(T_tool, T)
    assert np.array_equal(F, iarap.tet_boundary_faces(T))
    assert list(report["energies"]) == json.loads(run.stdout)["energies"]
    with pytest.raises(ValueError, match="tetrahedral"):
        iarap.deform_file(path, constraints=constraints, repair=True)
