"""An independent cotan Laplacian (numpy/scipy), the yardstick the report compares the library's operators with."""
from __future__ import annotations

import numpy as np
import scipy.sparse


def cotan_laplacian(V: np.ndarray, F: np.ndarray) -> scipy.sparse.csr_matrix:
    """-Delta, #V x #V: L(i,j) = -(cot a + cot b) / 2 on edge ij (one term on the boundary), zero row sums."""
    rows, cols, vals = [], [], []
    for k in range(3):
        o, i, j = F[:, k], F[:, (k + 1) % 3], F[:, (k + 2) % 3]
        a, b = V[i] - V[o], V[j] - V[o]
        half_cot = 0.5 * np.einsum("ij,ij->i", a, b) / np.linalg.norm(np.cross(a, b), axis=1)
        rows += [i, j, i, j]
        cols += [j, i, i, j]
        vals += [-half_cot, -half_cot, half_cot, half_cot]
    n = len(V)
    return scipy.sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                   shape=(n, n))


def relative_difference(A, B) -> float:
    """max |A - B| / max |B_ii|."""
    return float(abs(A - B).max() / abs(B.diagonal()).max())
