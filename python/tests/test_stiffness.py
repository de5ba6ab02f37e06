"""Per-vertex stiffness (issue 45, item 4) from Python: ARAP(stiffness=...) and deform_file(stiffness=...)
give the tool's numbers; a stiff band stays rigid; bad factors name the vertex."""
import json
import subprocess

import numpy as np
import pytest

import iarap

from conftest import REPO, bbox_diagonal, handle_scene, rigid_residual, y_band

BUNNY = REPO / "data" / "bunny.off"


def band(V, lo=0.45, hi=0.6):
    return y_band(V, lo, hi)


def test_ones_give_the_same_bytes_and_a_stiff_band_stays_rigid():
    V, F = iarap.read_mesh(BUNNY)
    fixed, targets = handle_scene(V, 0.15)
    U_plain = iarap.ARAP(V, F, fixed).solve(targets, iterations=20, accelerator="none")
    U_ones = iarap.ARAP(V, F, fixed, stiffness=np.ones(len(V))).solve(targets, iterations=20, accelerator="none")
    assert np.array_equal(U_plain, U_ones)
    s = np.ones(len(V))
    s[band(V)] = 1e6
    U_stiff = iarap.ARAP(V, F, fixed, stiffness=s).solve(targets, iterations=300, accelerator="none")
    d = bbox_diagonal(V)
    # measured: 7e-7 of the diagonal with the band, 1e-1 without (the issue asks for 1e-4)
    assert rigid_residual(V[band(V)], U_stiff[band(V)]) < 1e-4 * d
    assert rigid_residual(V[band(V)], U_plain[band(V)]) > 1e-2 * d


@pytest.mark.parametrize("bad, fragment", [(0.0, "vertex 5"), (-1.0, "vertex 5"), (np.nan, "vertex 5")])
def test_bad_factors_name_the_vertex(bad, fragment):
    V, F = iarap.read_mesh(BUNNY)
    s = np.ones(len(V))
    s[5] = bad
    with pytest.raises(ValueError, match=fragment):
        iarap.ARAP(V, F, [0, 1, 2], stiffness=s)
    with pytest.raises(ValueError, match="entries for a mesh of"):
        iarap.ARAP(V, F, [0, 1, 2], stiffness=np.ones(4))


def test_deform_file_gives_the_tool_numbers(cli, tmp_path):
    V, _ = iarap.read_mesh(BUNNY)
    path = tmp_path / "stiff.txt"
    path.write_text("".join(f"{i} {3.0 + (i % 7)}\n" for i in band(V)))
    scenario = REPO / "data" / "bunny_scenario.json"
    out = tmp_path / "tool.off"
    run = subprocess.run([str(cli), "deform", str(BUNNY), "--scenario", str(scenario), "--stiffness", str(path),
                          "--threads", "1", "--out", str(out), "--json", "--quiet"],
                         capture_output=True, text=True, check=True)
    iarap.set_thread_count(1)
    U, _, report = iarap.deform_file(BUNNY, scenario=scenario, stiffness=path)
    assert np.array_equal(U, iarap.read_mesh(out)[0])
    assert list(report["energies"]) == json.loads(run.stdout)["energies"]
    bad = tmp_path / "bad.txt"
    bad.write_text("3 2\n3 4\n")
    with pytest.raises(ValueError, match="bad.txt:2"):
        iarap.deform_file(BUNNY, scenario=scenario, stiffness=bad)
