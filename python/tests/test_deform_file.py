"""iarap.deform_file: the job of `iarap deform` from Python (the library's prepare_deform and solve_deform),
the same numbers as the tool for the same files and options, through every option kind."""
import json
import math
import subprocess

import numpy as np
import pytest

import iarap

from conftest import REPO

BUNNY = REPO / "data" / "bunny.off"


def tool(cli, tmp_path, *args):
    out = tmp_path / "tool.off"
    run = subprocess.run([str(cli), "deform", str(BUNNY), *map(str, args), "--out", str(out), "--json", "--quiet"],
                         capture_output=True, text=True, check=True)
    return iarap.read_mesh(out)[0], json.loads(run.stdout)


@pytest.mark.parametrize("args, kwargs", [
    (["--scenario", REPO / "data" / "bunny_scenario.json", "--iterations", 7, "--accel", "none"],
     dict(scenario=REPO / "data" / "bunny_scenario.json", iterations=7, accelerator="none")),
    (["--constraints", REPO / "data" / "bunny_constraints.txt", "--method", "spokes-rims", "--tolerance", 1e-9],
     dict(constraints=REPO / "data" / "bunny_constraints.txt", method="spokes-rims", tolerance=1e-9)),
    (["--scenario", REPO / "data" / "bunny_scenario.json", "--gravity", 0, -1, 0, "--density", 2],
     dict(scenario=REPO / "data" / "bunny_scenario.json", gravity=(0, -1, 0), density=2.0)),
])
def test_the_same_numbers_as_the_tool(cli, tmp_path, args, kwargs):
    U_tool, report_tool = tool(cli, tmp_path, *args, "--threads", 1)
    iarap.set_thread_count(1)
    U, F, report = iarap.deform_file(BUNNY, **kwargs)
    V, F_file = iarap.read_mesh(BUNNY)
    assert np.array_equal(F, F_file) and U.shape == V.shape
    # The tool writes OFF with every digit of a double: the positions come back exactly.
    assert np.array_equal(U, U_tool)
    for key in ("iterations", "stop_reason", "energies", "energy", "constrained", "planar"):
        assert report[key] == pytest.approx(report_tool[key], rel=1e-15) if key == "energies" else \
            report[key] == report_tool[key], key


def test_bad_input_is_named(tmp_path):
    with pytest.raises(iarap.InputError, match="exactly one of scenario= and constraints="):
        iarap.deform_file(BUNNY)
    with pytest.raises(iarap.InputError, match=r"tolerance must be a finite number; got nan"):
        iarap.deform_file(BUNNY, constraints=REPO / "data" / "bunny_constraints.txt", tolerance=math.nan)
    with pytest.raises(iarap.InputError, match="density must be a finite number > 0"):
        iarap.deform_file(BUNNY, constraints=REPO / "data" / "bunny_constraints.txt", gravity=(0, -1, 0), density=0)
    bad = tmp_path / "c.txt"
    bad.write_text("0 0 0 0\n99999 1 2 3\n")
    with pytest.raises(iarap.InputError, match="c.txt:2"):
        iarap.deform_file(BUNNY, constraints=bad)
