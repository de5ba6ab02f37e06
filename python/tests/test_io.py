"""read_mesh, write_mesh and check_mesh."""
import numpy as np
import pytest

import iarap
from conftest import REPO


def test_read_mesh_shapes_and_dtypes(bunny):
    V, F = bunny
    assert V.shape == (3485, 3) and V.dtype == np.float64 and V.flags.c_contiguous
    assert F.shape == (6966, 3) and F.dtype == np.int64 and F.flags.c_contiguous
    assert F.min() == 0 and F.max() == len(V) - 1


@pytest.mark.parametrize("extension", ["off", "obj", "ply"])
def test_write_then_read_is_exact(bunny, tmp_path, extension):
    V, F = bunny
    U = V + np.random.default_rng(3).normal(scale=1e-3, size=V.shape)  # full 17-digit coordinates
    path = tmp_path / f"mesh.{extension}"
    iarap.write_mesh(path, U, F)
    U_read, F_read = iarap.read_mesh(str(path))
    np.testing.assert_array_equal(U_read, U)
    np.testing.assert_array_equal(F_read, F)


def test_check_mesh_of_the_bunny(bunny):
    report = iarap.check_mesh(*bunny)
    assert report["usable"] and report["errors"] == []
    assert report["vertices"] == 3485 and report["faces"] == 6966
    assert report["components"] == 1 and report["genus"] == 0 and report["boundary_edges"] == 0
    assert report["non_delaunay_edges"] > 0  # the bunny is 9% non-Delaunay (shared/meshes/README.md)


def test_check_mesh_reports_bad_data_instead_of_raising(bunny):
    V, F = bunny
    V = V.copy()
    V[5, 1] = np.nan
    F = F.copy()
    F[7, 2] = len(V) + 10
    report = iarap.check_mesh(V, F)
    assert not report["usable"]
    assert report["non_finite_coordinates"] == 1 and report["out_of_range_indices"] == 1
    assert any("vertex 5" in e for e in report["errors"])
    assert any("face 7" in e for e in report["errors"])


def test_check_mesh_non_manifold_edge():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], dtype=float)
    F = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    report = iarap.check_mesh(V, F)
    assert report["non_manifold_edges"] == 1 and not report["usable"] and report["genus"] is None


def test_check_mesh_wrong_column_count_is_reported(bunny):
    V, F = bunny
    report = iarap.check_mesh(V, np.hstack([F, F[:, :1]]))
    assert not report["usable"] and "F #F x 3" in report["errors"][0]


def test_read_mesh_errors_name_the_file(tmp_path):
    with pytest.raises(ValueError, match="missing.off"):
        iarap.read_mesh(tmp_path / "missing.off")
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    with pytest.raises(iarap.InputError, match="bad.off:6"):
        iarap.read_mesh(bad)
    with pytest.raises(ValueError, match="xyz"):
        iarap.read_mesh(REPO / "data" / "bunny.xyz")
    with pytest.raises(TypeError):
        iarap.read_mesh(42)
