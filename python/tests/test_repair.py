"""iarap.repair_mesh and `iarap repair` (issue 47 item 2): the same repair, a map that round-trips, and soft
constraints carried over `deform --repair`."""
import json
import subprocess

import numpy as np

import iarap


def cones():
    """Two closed square pyramids touching at their tips (vertex 0): a non-manifold vertex."""
    V = np.array([[0, 0, 0], [1, 0, 1], [0, 1, 1], [-1, 0, 1], [0, -1, 1],
                  [1, 0, -1], [0, 1, -1], [-1, 0, -1], [0, -1, -1]], float)
    F = np.array([[0, 2, 1], [0, 3, 2], [0, 4, 3], [0, 1, 4], [1, 2, 3], [1, 3, 4],
                  [0, 5, 6], [0, 6, 7], [0, 7, 8], [0, 8, 5], [5, 7, 6], [5, 8, 7]])
    return V, F


def test_repair_mesh_splits_the_tip_and_its_map_round_trips():
    V, F = cones()
    F = np.vstack([F, F[3][::-1], F[8]])  # a reversed copy of face 3 and a repeat of face 8: both dropped
    V2, F2, new_to_old, report = iarap.repair_mesh(V, F)
    assert V2.shape == (10, 3) and F2.shape == (12, 3)
    assert report["split_vertices"] == 1 and report["vertex_copies"] == 1 and report["duplicate_faces"] == 2
    assert new_to_old[9] == 0 and np.array_equal(V2[9], V[0])
    # Every output vertex stands for an input vertex at its position, every input vertex faces use appears.
    assert np.array_equal(V2, V[new_to_old])
    assert set(new_to_old) == set(np.unique(F))
    old_to_new = report["old_to_new"]
    assert all(new_to_old[old_to_new[v]] == v for v in range(len(V)))
    assert iarap.check_mesh(V2, F2)["usable"]


def test_the_tool_and_python_give_the_same_repair(cli, tmp_path):
    V, F = cones()
    mesh = tmp_path / "cones.off"
    iarap.write_mesh(mesh, V, F)
    out, report = tmp_path / "fixed.off", tmp_path / "report.json"
    run = subprocess.run([str(cli), "repair", str(mesh), "--out", str(out), "--report", str(report), "--json"],
                         capture_output=True, text=True, check=True)
    printed, written = json.loads(run.stdout), json.loads(report.read_text())
    assert printed == written
    V2, F2, _, py_report = iarap.repair_mesh(V, F)
    V_tool, F_tool = iarap.read_mesh(out)
    assert np.array_equal(V_tool, V2) and np.array_equal(F_tool, F2)
    assert all(written["counts"][k] == py_report[k] for k in written["counts"])


def test_deform_repair_carries_soft_constraints(cli, tmp_path):
    V, F = cones()
    mesh = tmp_path / "cones.off"
    iarap.write_mesh(mesh, V, F)
    constraints = tmp_path / "c.txt"
    constraints.write_text("1 1 0 1\n5 1 0 -1\n"       # a base vertex of each cone, at rest
                           "0 0.2 0 0 4\n"             # the tip, pulled sideways (W = 4, shared by its copies)
                           "b 7 0.2 0.3 0.5 0 0 -1 1\n")  # a point on a face of the lower cone, at the copy
    out = tmp_path / "out.off"
    run = subprocess.run([str(cli), "deform", str(mesh), "--constraints", str(constraints), "--repair", "--out",
                          str(out), "--json", "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    U, _ = iarap.read_mesh(out)
    assert U.shape == (10, 3) and np.isfinite(U).all()
    assert report["soft"] == 3  # the tip's two copies and the face point
    # Both copies of the tip are pulled toward x = 0.2 (they moved; the bases stayed).
    assert U[0, 0] > 0.01 and U[9, 0] > 0.01


def test_keep_numbering_gives_the_input_numbering(cli, tmp_path):
    V, F = cones()
    mesh = tmp_path / "cones.off"
    iarap.write_mesh(mesh, V, F)
    constraints = tmp_path / "c.txt"
    constraints.write_text("1 1 0 1\n5 1 0 -1\n0 0.2 0 0 4\n")
    out = tmp_path / "out.off"
    run = subprocess.run([str(cli), "deform", str(mesh), "--constraints", str(constraints), "--repair",
                          "--keep-numbering", "--out", str(out), "--json", "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    U, F_out = iarap.read_mesh(out)
    assert U.shape == V.shape and np.array_equal(F_out, F)
    # The tip is the mean of its two copies; the report gives how far they lie from it.
    U_split, _, _ = iarap.deform_file(mesh, constraints=constraints, repair=True)
    assert np.allclose(U[0], (U_split[0] + U_split[9]) / 2, rtol=0, atol=1e-15)
    spread = json.loads(run.stdout)["copies_spread"]
    assert abs(spread - np.linalg.norm(U_split[0] - U_split[9]) / 2) < 1e-15
    U_py, F_py, report = iarap.deform_file(mesh, constraints=constraints, repair=True, keep_numbering=True)
    assert np.array_equal(U_py, U) and np.array_equal(F_py, F) and report["copies_spread"] == spread
    refused = subprocess.run([str(cli), "deform", str(mesh), "--constraints", str(constraints), "--keep-numbering",
                              "--out", str(out)], capture_output=True, text=True)
    assert refused.returncode == 2 and "--repair" in refused.stderr
