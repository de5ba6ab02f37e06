"""deform_file(volume=True) (issue 45, item 3): the closed surface deformed as a solid gives the tool's
numbers, comes back with its own vertices and faces, and keeps its volume better than surface iARAP."""
import json
import shutil
import subprocess

import numpy as np
import pytest

import iarap

from conftest import REPO

BUNNY = REPO / "data" / "bunny.off"
BEND60 = REPO / "data" / "bend60_scenario.json"

needs_tetgen = pytest.mark.skipif(shutil.which("tetgen") is None,
                                  reason="the tetgen program is not on PATH (apt-get install tetgen)")


@needs_tetgen
def test_volume_gives_the_tool_numbers_and_keeps_the_volume(cli, tmp_path):
    out = tmp_path / "solid.off"
    run = subprocess.run([str(cli), "deform", str(BUNNY), "--scenario", str(BEND60), "--volume", "--iterations", "10",
                          "--threads", "1", "--out", str(out), "--json", "--quiet"],
                         capture_output=True, text=True, check=True)
    tool = json.loads(run.stdout)
    iarap.set_thread_count(1)
    V, F = iarap.read_mesh(BUNNY)
    U, F_out, report = iarap.deform_file(BUNNY, scenario=BEND60, volume=True, iterations=10)
    assert U.shape == V.shape and np.array_equal(F_out, F)  # the surface's own vertices and faces
    assert np.array_equal(U, iarap.read_mesh(out)[0])
    assert list(report["energies"]) == tool["energies"]
    assert report["volume_ratio"] == pytest.approx(tool["volume_ratio"], rel=1e-12)
    assert tool["tetrahedra"] > 0 and tool["interior_points"] > 0 and tool["vertices"] == len(V)
    _, _, shell = iarap.deform_file(BUNNY, scenario=BEND60, iterations=10)
    assert abs(report["volume_ratio"] - 1) < abs(shell["volume_ratio"] - 1)


def test_open_surface_is_refused(tmp_path):
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    F = np.array([[0, 1, 2], [1, 3, 2]])
    mesh = tmp_path / "open.off"
    iarap.write_mesh(mesh, V, F)
    constraints = tmp_path / "c.txt"
    constraints.write_text("0 0 0 0\n1 1 0 0\n2 0 1 0.1\n")
    with pytest.raises(ValueError, match="closed surface"):
        iarap.deform_file(mesh, constraints=constraints, volume=True)
