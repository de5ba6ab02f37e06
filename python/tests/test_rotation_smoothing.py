"""Rotation smoothing (issue 45, item 1) from Python and the command line: ARAP.solve(rotation_smoothing=...)
and `iarap deform --rotation-smoothing`; 0 is the solver without it, Newton and plain reach the same minimum,
and bad values, UV maps and tetrahedral meshes are refused with the option's name."""
import subprocess

import numpy as np
import pytest

import iarap

from conftest import REPO, bbox_diagonal, handle_scene

BUNNY = REPO / "data" / "bunny.off"


def test_zero_is_the_solver_without_it_and_a_positive_alpha_changes_the_shape():
    V, F = iarap.read_mesh(BUNNY)
    fixed, targets = handle_scene(V, 0.15)
    solver = iarap.ARAP(V, F, fixed)
    U_default = solver.solve(targets, iterations=10)
    U_zero = solver.solve(targets, iterations=10, rotation_smoothing=0.0)
    assert np.array_equal(U_default, U_zero)
    U_smooth = solver.solve(targets, iterations=10, rotation_smoothing=0.2)
    # measured 0.021 of the diagonal: the term is not idle.
    assert np.abs(U_smooth - U_default).max() > 1e-3 * bbox_diagonal(V)


def test_newton_and_plain_reach_the_same_minimum():
    V, F = iarap.read_mesh(BUNNY)
    fixed, targets = handle_scene(V, 0.15)
    solver = iarap.ARAP(V, F, fixed)
    U_newton = solver.solve(targets, iterations=100, tolerance=1e-12, rotation_smoothing=0.02)
    newton = solver.report
    U_plain = solver.solve(targets, iterations=1000, tolerance=1e-12, accelerator="none", rotation_smoothing=0.02)
    plain = solver.report
    assert newton["converged"] and plain["converged"]
    assert newton["iterations"] * 5 <= plain["iterations"]
    # The energy rule stops both within ~1e-12 of the minimum's energy: positions to ~sqrt of that.
    assert np.abs(U_newton - U_plain).max() < 1e-6 * bbox_diagonal(V)
    energies = np.asarray(plain["energies"])
    assert np.all(np.diff(energies) <= 1e-12 * energies[:-1])  # plain never raises the energy


def test_bad_values_and_unsupported_problems_are_refused():
    V, F = iarap.read_mesh(BUNNY)
    fixed, targets = handle_scene(V, 0.15)
    solver = iarap.ARAP(V, F, fixed)
    with pytest.raises(iarap.InputError, match="rotation_smoothing must be a finite number >= 0; got -1"):
        solver.solve(targets, rotation_smoothing=-1.0)
    with pytest.raises(iarap.InputError, match="rotation_smoothing must be a finite number >= 0; got nan"):
        solver.solve(targets, rotation_smoothing=float("nan"))


def test_the_command_line_takes_the_flag(cli, tmp_path):
    out = tmp_path / "out.off"
    scenario = REPO / "data" / "bend60_scenario.json"
    run = subprocess.run([str(cli), "deform", str(BUNNY), "--scenario", str(scenario), "--out", str(out),
                          "--rotation-smoothing", "0.02", "--iterations", "5"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    refused = subprocess.run([str(cli), "deform", str(BUNNY), "--scenario", str(scenario), "--out", str(out),
                              "--rotation-smoothing", "-0.5"], capture_output=True, text=True)
    assert refused.returncode == 2
    assert "rotation_smoothing must be a finite number >= 0; got -0.5" in refused.stderr, refused.stderr
