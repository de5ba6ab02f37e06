#!/usr/bin/env python3
"""Plot the energy per iteration of the three ARAP energies on one deformation of a mesh.

Each curve is E(U_k) / E(U_0): the energies differ in scale (different discretizations), their decrease
is what local/global iterations are judged by. Saves a PNG (matplotlib, no display needed).

    PYTHONPATH=build/python /usr/bin/python3 python/examples/energy_curves.py --out out/energy_curves.png
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after the backend choice)
import numpy as np  # noqa: E402

import iarap  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default=REPO / "data" / "bunny.off", help="input mesh (default: the bunny)")
    parser.add_argument("--out", default="energy_curves.png", help="output image (.png .pdf .svg)")
    parser.add_argument("--iterations", type=int, default=50)
    args = parser.parse_args()

    V, F = iarap.read_mesh(args.mesh)
    # The bench scene: bottom 10% along y fixed, top 10% moved by 10% of the bounding-box diagonal along x.
    y = V[:, 1]
    height = y.max() - y.min()
    bottom = np.flatnonzero(y <= y.min() + 0.1 * height)
    top = np.flatnonzero(y >= y.max() - 0.1 * height)
    fixed = np.concatenate([bottom, top])
    targets = V[fixed].copy()
    targets[len(bottom):, 0] += 0.1 * np.linalg.norm(V.max(axis=0) - V.min(axis=0))

    figure, axes = plt.subplots(figsize=(6, 4))
    for method in iarap.ARAP_METHODS:
        solver = iarap.ARAP(V, F, fixed=fixed, method=method)
        solver.solve(targets, iterations=args.iterations, tolerance=-1)  # every method runs every iteration
        report = solver.report
        relative = np.concatenate([[1.0], report["energies"] / report["initial_energy"]])
        axes.semilogy(np.arange(len(relative)), relative, label=method)
        per_iteration = (report["local_ms"] + report["global_ms"]) / report["iterations"]
        print(f"{method:12s} E_0 {report['initial_energy']:.6g}  E_{report['iterations']} "
              f"{report['energies'][-1]:.6g}  ({per_iteration:.2f} ms per iteration)")
    axes.set_xlabel("iteration")
    axes.set_ylabel("energy / initial energy")
    axes.set_title(f"{pathlib.Path(args.mesh).name}: {len(V)} vertices, {len(fixed)} constrained")
    axes.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
