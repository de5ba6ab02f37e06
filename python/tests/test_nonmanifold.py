"""Meshes that are not oriented manifolds (issue 47, item 1): iARAP on the tufted cover, original ARAP and
spokes-and-rims on the input's edges and faces, from Python (ARAP and deform_file); docs/nonmanifold.md."""
import numpy as np
import pytest

import iarap


def fin(faces):
    """`faces` triangles standing on the edge (0, 1), every second one the other way round."""
    V = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
    F = []
    for i in range(faces):
        angle = 2 * np.pi * i / faces + 0.1 * i
        V.append([0.5 + 0.1 * i, np.cos(angle), np.sin(angle)])
        F.append([0, 1, i + 2] if i % 2 == 0 else [1, 0, i + 2])
    return np.array(V), np.array(F)


@pytest.mark.parametrize("method", ["iarap", "arap", "spokes-rims"])
def test_a_fin_deforms_and_stays_at_rest(method):
    V, F = fin(4)
    arap = iarap.ARAP(V, F, [0, 1], method=method)
    # Rest targets: the rest shape, to roundoff of the unit-sized mesh.
    U = arap.solve(V[[0, 1]], V.copy())
    assert U.shape == V.shape and np.abs(U - V).max() < 1e-9
    assert np.isfinite(arap.min_weight)
    if method == "iarap":
        assert arap.intrinsic["tufted_cover"] and arap.intrinsic["cover_vertices"] == len(V)
        assert arap.min_weight >= -1e-12  # an intrinsic Delaunay triangulation: no negative weight
    moved = V[[0, 1]].copy()
    moved[1, 1] += 0.2
    U = arap.solve(moved, V.copy())
    assert np.isfinite(U).all() and np.array_equal(U[1], moved[1])


def test_deform_file_takes_a_fin_without_repair(tmp_path):
    V, F = fin(3)
    mesh = tmp_path / "fin.obj"
    iarap.write_mesh(mesh, V, F)
    constraints = tmp_path / "c.txt"
    constraints.write_text("0 0 0 0\n1 1 0.2 0\n")
    U, F_out, report = iarap.deform_file(mesh, constraints=constraints)
    assert U.shape == V.shape and np.array_equal(F_out, F)
    assert report["tufted_cover"] and report["min_weight"] >= -1e-12
    assert any("non-manifold" in w for w in report["warnings"])
