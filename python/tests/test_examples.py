"""The example scripts run and write what they say."""
import os
import subprocess
import sys

import numpy as np

import iarap
from conftest import REPO

EXAMPLES = REPO / "python" / "examples"


def run_example(name, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    # The folder holding the package first, so that the scripts import the package under test.
    package_parent = os.path.dirname(os.path.dirname(iarap.__file__))
    env["PYTHONPATH"] = os.pathsep.join([package_parent, env.get("PYTHONPATH", "")])
    return subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], capture_output=True, text=True,
                          check=True, env=env, timeout=600)


def test_deform_bunny(tmp_path):
    out = tmp_path / "bunny_deformed.off"
    run = run_example("deform_bunny.py", "--out", out, "--iterations", 20)
    assert "wrote" in run.stdout
    V, F = iarap.read_mesh(REPO / "data" / "bunny.off")
    U, F_out = iarap.read_mesh(out)
    np.testing.assert_array_equal(F_out, F)
    moved = np.linalg.norm(U - V, axis=1)
    diagonal = np.linalg.norm(V.max(axis=0) - V.min(axis=0))
    assert moved.max() > 0.05 * diagonal  # the ears moved by about 10% of the diagonal
    bottom = V[:, 1] <= V[:, 1].min() + 0.1 * (V[:, 1].max() - V[:, 1].min())
    assert moved[bottom].max() <= 1e-12 * diagonal  # the fixed feet stayed (17-digit file round trip)


def test_energy_curves(tmp_path):
    out = tmp_path / "curves.png"
    run = run_example("energy_curves.py", "--out", out, "--iterations", 10)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    lines = [line for line in run.stdout.splitlines() if line.split()[0] in iarap.ARAP_METHODS]
    assert len(lines) == 3


def test_tutorial():
    run = run_example("tutorial.py", "--iterations", 10, "--eigenpairs", 4)
    lines = run.stdout.splitlines()
    assert lines[0].startswith("mesh: 3485 vertices, 6966 faces, genus 0")
    methods = [line.split() for line in lines if line.split()[0] in iarap.ARAP_METHODS]
    assert [m[0] for m in methods] == list(iarap.ARAP_METHODS)
    for m in methods:
        initial, final = float(m[2]), float(m[4])
        assert final < initial  # every method decreases its energy
        # iARAP and spokes-and-rims are sums of non-negative terms; original ARAP's negative cotan weights
        # on the bunny's non-Delaunay edges take its energy below zero (README, first section).
        assert (final < 0) == (m[0] == "arap")
    values = [float(v) for v in next(line for line in lines if line.startswith("eigenvalues")).split(":")[1].split()]
    # The constant vector is in the kernel: lambda_0 is zero up to the solver's round-off relative to lambda_1
    # (shift-invert at -1e-6 / diagonal^2 resolves it to ~1e-6 of lambda_1 at worst); then increasing.
    assert abs(values[0]) < 1e-6 * values[1]
    assert all(a < b for a, b in zip(values[1:], values[2:]))
    gram_error = float(lines[-1].split("=")[1])
    assert gram_error < 1e-8  # eigsh returns M-orthonormal vectors up to round-off
