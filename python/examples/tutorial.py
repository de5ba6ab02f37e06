#!/usr/bin/env python3
"""A tour of the iarap Python package in five steps, on the bundled bunny.

1. read a mesh and check it;  2. choose constraints (fixed vertices and where they go);
3. deform with the three energies;  4. compare their energies;  5. the Laplace-Beltrami eigenfunctions of
the intrinsic Laplacian with its mass matrix (scipy.sparse.linalg.eigsh, L u = lambda M u).

    pip install --no-build-isolation .    # once (see README, "Python")
    python3 python/examples/tutorial.py
"""
import argparse
import pathlib

import numpy as np
import scipy.sparse.linalg

import iarap

REPO = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default=REPO / "data" / "bunny.off", help="input mesh (default: the bunny)")
    parser.add_argument("--iterations", type=int, default=30)
    parser.add_argument("--eigenpairs", type=int, default=6)
    args = parser.parse_args()

    # 1. A mesh is two arrays: V (#V, 3) float64 positions, F (#F, 3) int64 vertex indices.
    V, F = iarap.read_mesh(args.mesh)
    report = iarap.check_mesh(V, F)
    print(f"mesh: {report['vertices']} vertices, {report['faces']} faces, genus {report['genus']}, "
          f"{report['non_delaunay_edges']} non-Delaunay edges, usable: {report['usable']}")

    # 2. Constraints: vertex indices and their target positions, targets[k] for fixed[k]. Here the bottom
    #    10% (along y) stays and the top 10% moves sideways by 10% of the bounding-box diagonal.
    y = V[:, 1]
    height = y.max() - y.min()
    bottom = np.flatnonzero(y <= y.min() + 0.1 * height)
    top = np.flatnonzero(y >= y.max() - 0.1 * height)
    diagonal = np.linalg.norm(V.max(axis=0) - V.min(axis=0))
    fixed = np.concatenate([bottom, top])
    targets = V[fixed].copy()
    targets[len(bottom):, 0] += 0.1 * diagonal
    print(f"constraints: {len(bottom)} fixed, {len(top)} moved by {0.1 * diagonal:.4g}")

    # 3.-4. One solver per energy: the constructor factorizes once, solve() iterates; report["energies"]
    #    holds the energy after each iteration (squared mesh units). Original ARAP keeps the negative cotan
    #    weights of non-Delaunay edges: on the bunny its energy goes below zero, iARAP's cannot.
    for method in iarap.ARAP_METHODS:
        solver = iarap.ARAP(V, F, fixed=fixed, method=method)
        U = solver.solve(targets, iterations=args.iterations)
        energies = solver.report["energies"]
        moved = np.linalg.norm(U - V, axis=1).max() / diagonal
        print(f"{method:12s} energy {solver.report['initial_energy']:.6g} -> {energies[-1]:.6g} in "
              f"{solver.report['iterations']} iterations, largest displacement {moved:.3f} x diagonal")

    # 5. Eigenfunctions: L u = lambda M u with the intrinsic cotan Laplacian and its mass matrix (intrinsic
    #    Voronoi cells). Shift-invert about a small negative sigma finds the smallest eigenvalues; the first
    #    is 0 (constants), the others grow like those of the smooth surface.
    L, M = iarap.laplacian(V, F, kind="intrinsic", return_mass=True)
    values, vectors = scipy.sparse.linalg.eigsh(L, k=args.eigenpairs, M=M, sigma=-1e-6 / diagonal**2)
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    print("eigenvalues (1 / mesh units^2): " + " ".join(f"{v:.6g}" for v in values))
    # M-orthonormal: vectors^T M vectors = identity.
    gram = vectors.T @ (M @ vectors)
    print(f"max |U^T M U - I| = {np.abs(gram - np.eye(len(values))).max():.2e}")


if __name__ == "__main__":
    main()
