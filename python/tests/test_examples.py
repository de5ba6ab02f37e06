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
    # The module's folder first, so that the scripts import the module under test.
    env["PYTHONPATH"] = os.pathsep.join([os.path.dirname(iarap.__file__), env.get("PYTHONPATH", "")])
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
