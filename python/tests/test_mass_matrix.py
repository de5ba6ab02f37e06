"""iarap.mass_matrix and laplacian(..., return_mass=True) against independent numpy derivations."""
import numpy as np
import pytest
import scipy.sparse
import scipy.sparse.linalg

import iarap
from conftest import icosphere


def triangle_areas(V, F):
    return 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)


def circumcentric_cells(V, F):
    """Area of each vertex's circumcentric (Voronoi) cell from the circumcentres themselves: in every
    triangle, corner i gets the quadrilateral (v_i, middle of v_i v_j, circumcentre, middle of v_i v_k),
    two triangles. Valid for acute triangles (the circumcentre lies inside)."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    centre = a + (np.cross(n, ab) * (ac * ac).sum(1)[:, None] + np.cross(ac, n) * (ab * ab).sum(1)[:, None]) / (
        2 * (n * n).sum(1)[:, None])
    cells = np.zeros(len(V))
    for k in range(3):
        p, q, r = V[F[:, k]], V[F[:, (k + 1) % 3]], V[F[:, (k + 2) % 3]]
        m_pq, m_pr = (p + q) / 2, (p + r) / 2
        part = 0.5 * (np.linalg.norm(np.cross(m_pq - p, centre - p), axis=1)
                      + np.linalg.norm(np.cross(centre - p, m_pr - p), axis=1))
        np.add.at(cells, F[:, k], part)
    return cells


def diagonal(M):
    assert scipy.sparse.isspmatrix_csr(M) and M.nnz == M.shape[0]  # lumped: diagonal only
    return M.diagonal()


def test_barycentric_is_a_third_of_each_triangle(bunny):
    V, F = bunny
    expected = np.zeros(len(V))
    for k in range(3):
        np.add.at(expected, F[:, k], triangle_areas(V, F) / 3)
    # Sums of <= ~10 positive terms: agreement to a few ulps of the cell.
    np.testing.assert_allclose(diagonal(iarap.mass_matrix(V, F, kind="barycentric")), expected, rtol=1e-13)


def test_voronoi_on_an_acute_mesh_is_the_circumcentric_cell(sphere):
    V, F = sphere
    # The icosphere's triangles are all acute, so the mixed cells are the circumcentric ones; the library
    # uses cotangents, the reference the circumcentres: equal up to round-off of a few ulps.
    np.testing.assert_allclose(diagonal(iarap.mass_matrix(V, F)), circumcentric_cells(V, F), rtol=1e-12)
    # The mesh is Delaunay: no flip, the intrinsic cells are the same.
    np.testing.assert_allclose(diagonal(iarap.mass_matrix(V, F, kind="intrinsic")), circumcentric_cells(V, F),
                               rtol=1e-12)


@pytest.mark.parametrize("kind", iarap.MASS_KINDS)
def test_cells_partition_the_surface(bunny, kind):
    V, F = bunny
    cells = diagonal(iarap.mass_matrix(V, F, kind=kind))
    assert cells.min() > 0
    # ~7000 positive terms: the sum agrees with the surface area to 1e-12 relative.
    assert abs(cells.sum() - triangle_areas(V, F).sum()) <= 1e-12 * triangle_areas(V, F).sum()


def test_mass_scales_with_area(sphere):
    V, F = sphere
    for kind in iarap.MASS_KINDS:
        np.testing.assert_allclose(diagonal(iarap.mass_matrix(3.0 * V, F, kind)),
                                   9.0 * diagonal(iarap.mass_matrix(V, F, kind)), rtol=1e-13)


def test_laplacian_with_mass(bunny):
    V, F = bunny
    for kind, default_mass in [("cotan", "voronoi"), ("intrinsic", "intrinsic"), ("iarap", "intrinsic")]:
        L, M = iarap.laplacian(V, F, kind=kind, return_mass=True)
        assert (abs(L - iarap.laplacian(V, F, kind=kind)) > 0).nnz == 0  # the same operator as alone
        np.testing.assert_array_equal(M.toarray().diagonal(), diagonal(iarap.mass_matrix(V, F, default_mass)))
    _, M = iarap.laplacian(V, F, return_mass=True, mass="barycentric")
    np.testing.assert_array_equal(diagonal(M), diagonal(iarap.mass_matrix(V, F, "barycentric")))


def test_sphere_spectrum(sphere):
    """-Delta on the unit sphere has eigenvalues l (l + 1) with multiplicity 2 l + 1: 0, then 2 (x3), 6 (x5)."""
    V, F = sphere
    L, M = iarap.laplacian(V, F, kind="intrinsic", return_mass=True)
    values = np.sort(scipy.sparse.linalg.eigsh(L, k=9, M=M, sigma=-1e-6, return_eigenvectors=False))
    assert abs(values[0]) < 1e-8
    # The cotan Laplacian converges as O(h^2): with 642 vertices (h ~ 0.15) the low eigenvalues are within
    # 1% of the smooth ones (measured: 4e-7 for l = 1, whose eigenfunctions, the coordinates, are nearly
    # reproduced, and 0.57% for l = 2).
    np.testing.assert_allclose(values[1:4], 2.0, rtol=1e-2)
    np.testing.assert_allclose(values[4:9], 6.0, rtol=1e-2)
