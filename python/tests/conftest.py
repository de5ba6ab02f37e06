"""Fixtures shared by the Python tests: the bundled bunny, shared meshes, the CLI built beside the module."""
import os
import pathlib

import numpy as np
import pytest

import iarap

REPO = pathlib.Path(__file__).resolve().parents[2]


def shared_mesh(name):
    """Path of a shared test mesh ($IARAP_SHARED_MESHES, else ../shared/meshes beside the repo), or None."""
    folder = os.environ.get("IARAP_SHARED_MESHES") or REPO.parent / "shared" / "meshes"
    path = pathlib.Path(folder) / name
    return path if path.exists() else None


def build_dir():
    """The CMake build tree the imported package comes from (it lies in <build>/python/iarap/), or None."""
    folder = pathlib.Path(iarap.__file__).resolve().parents[2]
    return folder if (folder / "CMakeCache.txt").exists() else None


def bbox_diagonal(V):
    return float(np.linalg.norm(V.max(axis=0) - V.min(axis=0)))


def handle_scene(V, shift=0.1):
    """The bench scene: the bottom 10% of the bounding box along y fixed, the top 10% moved along +x by
    `shift` times the bounding-box diagonal. Returns (fixed, targets)."""
    y = V[:, 1]
    low, high = y.min(), y.max()
    bottom = np.flatnonzero(y <= low + 0.1 * (high - low))
    top = np.flatnonzero(y >= high - 0.1 * (high - low))
    fixed = np.concatenate([bottom, top])
    targets = V[fixed].copy()
    targets[len(bottom):, 0] += shift * bbox_diagonal(V)
    return fixed, targets


def random_rotation(seed):
    """A proper rotation (det +1) from the QR factorization of a random matrix."""
    Q, R = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    Q = Q * np.sign(np.diag(R))
    return Q if np.linalg.det(Q) > 0 else -Q


def icosphere(subdivisions):
    """Unit sphere from an icosahedron, each face split 1-to-4 `subdivisions` times: near-equilateral
    triangles, so a Delaunay mesh (every cotan weight positive), outward oriented."""
    t = (1 + 5 ** 0.5) / 2
    V = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    F = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
         [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    V = [np.array(v, dtype=float) / np.linalg.norm(v) for v in V]
    for _ in range(subdivisions):
        middle = {}

        def midpoint(i, j):
            key = (min(i, j), max(i, j))
            if key not in middle:
                m = V[i] + V[j]
                V.append(m / np.linalg.norm(m))
                middle[key] = len(V) - 1
            return middle[key]

        F = [g for a, b, c in F for ab, bc, ca in [(midpoint(a, b), midpoint(b, c), midpoint(c, a))]
             for g in ([a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca])]
    return np.array(V), np.array(F)


@pytest.fixture(scope="session")
def sphere():
    return icosphere(3)


def read_shared_mesh(name):
    path = shared_mesh(name)
    if path is None:
        # CI sets IARAP_REQUIRE_SHARED_MESHES=1: an incomplete ../shared must fail, not pass with skips.
        if os.environ.get("IARAP_REQUIRE_SHARED_MESHES") == "1":
            pytest.fail(f"shared mesh {name} is missing and IARAP_REQUIRE_SHARED_MESHES=1")
        pytest.skip(f"shared mesh {name} not found (../shared/meshes or $IARAP_SHARED_MESHES)")
    return iarap.read_mesh(path)


@pytest.fixture(scope="session")
def spike():
    """A flat disk-like patch with boundary (binary PLY); skipped when absent."""
    return read_shared_mesh("spike.ply")


@pytest.fixture(scope="session")
def bunny():
    return iarap.read_mesh(REPO / "data" / "bunny.off")


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("IARAP_CLI")
    if not path:
        folder = build_dir()
        path = folder / "iarap" if folder else None
    if not path or not pathlib.Path(path).exists():
        pytest.skip("the iarap CLI is not built beside the module (set IARAP_CLI to its path)")
    return pathlib.Path(path)


def y_band(V, lo, hi):
    """The vertices strictly between fractions lo and hi of the bounding box along y."""
    y = V[:, 1]
    a, b = y.min(), y.max()
    return np.flatnonzero((y > a + lo * (b - a)) & (y < a + hi * (b - a)))


def rigid_residual(A, B):
    """Largest distance of B's rows from the best rigid image of A's (Kabsch)."""
    a, b = A - A.mean(axis=0), B - B.mean(axis=0)
    U, _, Wt = np.linalg.svd(a.T @ b)
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Wt))])
    return float(np.abs(a @ (U @ D @ Wt) - b).max())
