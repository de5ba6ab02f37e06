"""laplacian() and intrinsic_delaunay(): scipy matrices with the properties the paper states."""
import numpy as np
import pytest
import scipy.sparse

import iarap

EPS = np.finfo(float).eps


def assert_rows_sum_to_zero(M):
    """|row sum| within rounding of the row's entries: each of the k terms adds at most eps |entry|."""
    sums = np.asarray(M.sum(axis=1)).ravel()
    magnitude = np.asarray(abs(M).sum(axis=1)).ravel()
    assert np.all(np.abs(sums) <= 16 * EPS * magnitude + 1e-300)


def test_kinds_are_listed():
    assert iarap.LAPLACIAN_KINDS == ("cotan", "intrinsic", "iarap", "iarap-plus", "iarap-sym", "iarap-refined")


@pytest.mark.parametrize("kind", ["cotan", "intrinsic", "iarap", "iarap-plus", "iarap-sym", "iarap-refined"])
def test_laplacian_rows_sum_to_zero(bunny, kind):
    V, F = bunny
    L = iarap.laplacian(V, F, kind=kind)
    assert isinstance(L, scipy.sparse.csr_matrix)
    assert L.shape == (len(V), len(V)) and L.dtype == np.float64
    assert_rows_sum_to_zero(L)
    assert np.all(L.diagonal() > 0)
    if kind != "iarap-plus":  # L+ is the one asymmetric operator (end of paper Section 6)
        assert abs(L - L.T).max() <= 1e-12 * abs(L).max()


def test_intrinsic_laplacian_has_nonnegative_weights(bunny):
    V, F = bunny
    L_cotan = iarap.laplacian(V, F, "cotan").tocoo()
    L_intrinsic = iarap.laplacian(V, F, "intrinsic").tocoo()
    off = lambda M: M.data[M.row != M.col]
    assert off(L_cotan).max() > 0  # negative cotan weights on the bunny's non-Delaunay edges
    assert off(L_intrinsic).max() <= 1e-12 * abs(L_intrinsic.data).max()  # Delaunay: all w_ij >= 0


def test_intrinsic_delaunay(bunny):
    V, F = bunny
    idt = iarap.intrinsic_delaunay(V, F)
    nE, nS = len(idt["E"]), len(idt["segments"]["edge"])
    assert idt["F"].shape == F.shape and idt["FE"].shape == F.shape and idt["E"].shape == (nE, 2)
    assert idt["non_delaunay_before"] > 0 and idt["non_delaunay_after"] == 0 and idt["flips"] > 0
    assert np.all(idt["length"] > 0)
    interior = ~idt["is_boundary"]
    assert np.all(idt["cot_weight"][interior] >= -1e-12)
    np.testing.assert_allclose(idt["corner_angle"].sum(axis=1), np.pi, rtol=1e-12)
    seg = idt["segments"]
    assert seg["edge_start"].shape == (nE + 1,) and seg["edge_start"][-1] == nS
    assert np.all(np.diff(seg["edge_start"]) >= 1)
    # The segments of an edge run from E[e, 0] to E[e, 1]: their rest vectors add up to the edge.
    s_sum = np.add.reduceat(seg["s_hat"], seg["edge_start"][:-1], axis=0)
    chord = V[idt["E"][:, 1]] - V[idt["E"][:, 0]]
    non_loop = idt["E"][:, 0] != idt["E"][:, 1]
    np.testing.assert_allclose(s_sum[non_loop], chord[non_loop], atol=1e-12 * np.abs(V).max())
    traces = idt["traces"]
    assert traces["start"].shape == (nE + 1,) and traces["start"][-1] == len(traces["t"])


def test_B_rows_have_at_most_three_entries_summing_to_zero(bunny):
    V, F = bunny
    idt = iarap.intrinsic_delaunay(V, F)
    B = idt["B"]
    seg = idt["segments"]
    assert isinstance(B, scipy.sparse.csr_matrix) and B.shape == (len(seg["edge"]), len(V))
    assert np.diff(B.indptr).max() <= 3
    assert_rows_sum_to_zero(B)
    # Row s of B is b_s: B V gives the rest segment vectors, and L_iarap = B^T D_w B (Eq. 17).
    np.testing.assert_allclose(B @ V, seg["s_hat"], rtol=0, atol=1e-12 * np.abs(V).max())
    L = B.T @ scipy.sparse.diags(seg["weight"]) @ B
    L_iarap = iarap.laplacian(V, F, "iarap")
    assert abs(L - L_iarap).max() <= 1e-12 * abs(L_iarap).max()


def test_refine_boundary_splits_obtuse_boundary_edges():
    # One triangle, obtuse at vertex 2: its boundary edge (0, 1) has a negative cotan weight. The altitude
    # from vertex 2 meets it in the middle (by symmetry), where refinement inserts one point.
    V = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.2, 0.0]])
    F = np.array([[0, 1, 2]])
    plain = iarap.intrinsic_delaunay(V, F)
    assert plain["obtuse_boundary_before"] == 1 and plain["cot_weight"].min() < 0
    assert plain["inserted_t"].shape == (0,)
    idt = iarap.intrinsic_delaunay(V, F, refine_boundary=True)
    assert idt["num_input_vertices"] == 3 and idt["obtuse_boundary_after"] == 0
    np.testing.assert_array_equal(idt["inserted_on"], [[0, 1]])
    np.testing.assert_allclose(idt["inserted_t"], [0.5], rtol=1e-12)
    assert idt["F"].shape == (2, 3) and idt["F"].max() == 3  # intrinsic vertex 3 is the inserted point
    assert idt["cot_weight"].min() >= -1e-12
    B = idt["B"]
    assert B.shape[1] == len(V) and np.diff(B.indptr).max() <= 3
    assert_rows_sum_to_zero(B)
