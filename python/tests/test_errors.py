"""Every bad input raises an iarap.Error naming what is wrong, also a ValueError (InputError, TopologyError) or,
for a solve that cannot proceed, a RuntimeError (SolverError); nothing crashes. Only an argument Python
cannot pass at all (a number where a path goes, a string where a number goes) is the built-in TypeError."""
import pathlib

import numpy as np
import pytest

import iarap

# A regular tetrahedron: the smallest closed manifold mesh.
V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=float)
F = np.array([[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]])
FIXED = np.array([0, 1])


def with_value(array, index, value):
    out = np.array(array, dtype=np.result_type(array, np.asarray(value)))
    out[index] = value
    return out


def solver():
    return iarap.ARAP(V, F, fixed=FIXED, method="arap")


CASES = {
    # positions
    "V four columns": (lambda: iarap.ARAP(np.hstack([V, V[:, :1]]), F, FIXED),
                       r"V must be a #rows x 3 \(or 2\) array, got shape \(4, 4\)"),
    "V two columns, not planar-capable": (lambda: iarap.laplacian(V[:, :2], F),
                                          r"V must be a #rows x 3 array, got shape \(4, 2\)"),
    "V 1-D": (lambda: iarap.ARAP(V.ravel(), F, FIXED), r"V must be .* got shape \(12,\)"),
    "V 3-D": (lambda: iarap.laplacian(V[None], F), r"V must be .* got shape \(1, 4, 3\)"),
    "V NaN": (lambda: iarap.ARAP(with_value(V, (2, 1), np.nan), F, FIXED), r"V row 2 column 1 is nan"),
    "V Inf": (lambda: iarap.intrinsic_delaunay(with_value(V, (3, 0), -np.inf), F), r"V row 3 column 0 is -inf"),
    "V complex": (lambda: iarap.ARAP(V + 0j, F, FIXED), r"V must hold real coordinates, got dtype complex128"),
    "V strings": (lambda: iarap.write_mesh("x.off", V.astype(str), F), r"V must hold real coordinates"),
    "V ragged": (lambda: iarap.check_mesh([[0, 0, 0], [1, 0]], F), r"V cannot be converted to a numeric array"),
    "V object": (lambda: iarap.ARAP(object(), F, FIXED), r"V must hold real coordinates, got dtype object"),
    # faces
    "F float": (lambda: iarap.ARAP(V, F.astype(float), FIXED), r"F must hold integer vertex indices, got dtype float64"),
    "F bool": (lambda: iarap.laplacian(V, F > 0), r"F must hold integer vertex indices, got dtype bool"),
    "F five columns": (lambda: iarap.ARAP(V, np.hstack([F, F[:, :2]]), FIXED),
                       r"F must be a #F x 3 array of vertex indices, got shape \(4, 5\)"),
    # four columns are tetrahedra (volumetric ARAP), checked as such
    "F four columns": (lambda: iarap.ARAP(V, np.hstack([F, F[:, :1]]), FIXED),
                       r"tetrahedron 0 \(0, 1, 2, 0\) uses vertex 0 twice"),
    "F negative": (lambda: iarap.ARAP(V, with_value(F, (1, 2), -1), FIXED),
                   r"F\[1, 2\] \(face 1\) is -1, not a vertex: indices are 0-based and the mesh has 4 vertices"),
    "F too large": (lambda: iarap.intrinsic_delaunay(V, with_value(F, (3, 0), 4)), r"F\[3, 0\] \(face 3\) is 4, not a vertex"),
    "F beyond int32": (lambda: iarap.laplacian(V, with_value(F, (0, 0), 2**40)), r"F\[0, 0\] \(face 0\) is 1099511627776"),
    "F beyond int64": (lambda: iarap.write_mesh("x.off", V, F.astype(np.uint64) + np.uint64(2**63)),
                       r"F\[0, 0\] \(face 0\) is 9223372036854775808, outside the range of a 32-bit index"),
    "F beyond int32 in check_mesh": (lambda: iarap.check_mesh(V, with_value(F, (0, 1), -2**35)),
                                     r"F\[0, 1\] \(face 0\) is -34359738368, outside the range of a 32-bit index"),
    # (A fin, F not manifold, is no error for ARAP: it deforms on the mesh as it is, docs/nonmanifold.md.)
    "F zero-area face": (lambda: iarap.ARAP(np.vstack([V, [[1, 0, 0]]]), np.vstack([F, [[0, 1, 4]]]), FIXED,
                                            method="arap"),
                         r"face 4 is degenerate"),
    "F not manifold, intrinsic": (lambda: iarap.intrinsic_delaunay(np.vstack([V, [[0, 0, 3]]]), np.vstack([F, [[0, 1, 4]]])),
                                  r"(?i)manifold"),
    # constrained vertices
    "fixed out of range": (lambda: iarap.ARAP(V, F, [0, 99]), r"fixed\[1\] is 99, not a vertex: .* 4 vertices"),
    "fixed negative": (lambda: iarap.ARAP(V, F, [-1]), r"fixed\[0\] is -1, not a vertex"),
    "fixed 2-D": (lambda: iarap.ARAP(V, F, [[0, 1]]), r"fixed must be a 1-D array of vertex indices, got shape \(1, 2\)"),
    "fixed scalar": (lambda: iarap.ARAP(V, F, 3), r"fixed must be a 1-D array of vertex indices, got shape \(\)"),
    "fixed float": (lambda: iarap.ARAP(V, F, [0.0, 1.5]), r"fixed must hold integer vertex indices, got dtype float64"),
    "fixed duplicate": (lambda: iarap.ARAP(V, F, [0, 2, 0]), r"fixed\[2\] = 0 repeats fixed\[0\]"),
    "fixed empty": (lambda: iarap.ARAP(V, F, []), r"constrained \(fixed\) vertex set is empty"),
    "fixed setter": (lambda: setattr(solver(), "fixed", [7]), r"fixed\[0\] is 7, not a vertex"),
    # solve arguments
    "targets rows": (lambda: solver().solve(V[:3]), r"targets must be a #fixed x 3 = 2 x 3 array, got shape \(3, 3\)"),
    "targets NaN": (lambda: solver().solve(with_value(V[FIXED], (0, 0), np.nan)), r"targets row 0 column 0 is nan"),
    "targets None": (lambda: solver().solve(None), r"targets must hold real coordinates, got dtype object"),
    "U0 shape": (lambda: solver().solve(V[FIXED], U0=V[:3]), r"U0 must be a #V x 3 = 4 x 3 array, got shape \(3, 3\)"),
    "U0 NaN": (lambda: solver().solve(V[FIXED], U0=with_value(V, (3, 2), np.nan)), r"U0 row 3 column 2 is nan"),
    "iterations negative": (lambda: solver().solve(V[FIXED], iterations=-1), r"^iterations must be an integer in \[0, 1000000\]; got -1$"),
    "tolerance NaN": (lambda: solver().solve(V[FIXED], tolerance=np.nan), r"^tolerance must be a finite number; got nan$"),
    "energy U shape": (lambda: solver().energy(V[:2]), r"U must be a #V x 3 = 4 x 3 array"),
    # choices and files
    "method": (lambda: iarap.ARAP(V, F, FIXED, method="bogus"), r"unknown ARAP method 'bogus'"),
    "laplacian kind": (lambda: iarap.laplacian(V, F, kind="bogus"), r"unknown Laplacian kind 'bogus'"),
    "write extension": (lambda: iarap.write_mesh("mesh.xyz", V, F), r"xyz"),
    "degenerate face without mollification": (
        lambda: iarap.intrinsic_delaunay(with_value(V, 3, V[1]), F, mollify=False), r"face"),
    "mass kind": (lambda: iarap.mass_matrix(V, F, kind="lumped"), r"unknown mass matrix kind 'lumped'"),
    "mass kind of laplacian": (lambda: iarap.laplacian(V, F, return_mass=True, mass="cells"),
                               r"unknown mass matrix kind 'cells'"),
    "mass V NaN": (lambda: iarap.mass_matrix(with_value(V, (0, 2), np.nan), F), r"V row 0 column 2 is nan"),
    "mass F out of range": (lambda: iarap.mass_matrix(V, with_value(F, (2, 1), 9)), r"F\[2, 1\] \(face 2\) is 9"),
    "mass not manifold, intrinsic": (
        lambda: iarap.mass_matrix(np.vstack([V, [[0, 0, 3]]]), np.vstack([F, [[0, 1, 4]]]), kind="intrinsic"),
        r"(?i)manifold"),
    # files (also in test_io.py)
    "read missing file": (lambda: iarap.read_mesh(pathlib.Path("no-such-folder") / "missing.off"), r"missing.off"),
    "read unknown extension": (lambda: iarap.read_mesh("bunny.xyz"), r"xyz"),
    "write into a missing folder": (lambda: iarap.write_mesh(pathlib.Path("no-such-folder") / "out.off", V, F),
                                    r"no-such-folder"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_raises_iarap_error_naming_it(name):
    call, message = CASES[name]
    with pytest.raises(iarap.Error, match=message) as error:
        call()
    assert isinstance(error.value, ValueError), type(error.value).__mro__
    assert type(error.value) in (iarap.InputError, iarap.TopologyError)


def test_malformed_file_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    with pytest.raises(iarap.InputError, match="bad.off:6"):
        iarap.read_mesh(bad)


def test_failed_solve_is_a_solver_error():
    # Two tetrahedra, the second without a constrained vertex: L_ff is singular.
    two_V = np.vstack([V, V + [10, 0, 0]])
    two_F = np.vstack([F, F + len(V)])
    with pytest.raises(iarap.Error, match="component") as error:
        iarap.ARAP(two_V, two_F, fixed=FIXED, method="arap")
    assert isinstance(error.value, iarap.SolverError) and isinstance(error.value, RuntimeError)


def test_errors_are_named_as_members_of_iarap():
    for cls in (iarap.Error, iarap.InputError, iarap.TopologyError, iarap.SolverError, iarap.ARAP):
        assert cls.__module__ == "iarap", cls
    with pytest.raises(iarap.InputError) as error:
        iarap.laplacian(V, F, kind="bogus")
    assert "iarap.InputError" in repr(error.type)


def test_error_classes():
    for name, builtin in [("InputError", ValueError), ("TopologyError", ValueError), ("SolverError", RuntimeError)]:
        cls = getattr(iarap, name)
        assert issubclass(cls, iarap.Error) and issubclass(cls, builtin)
    assert not issubclass(iarap.InputError, RuntimeError) and not issubclass(iarap.SolverError, ValueError)
    with pytest.raises(iarap.InputError):
        iarap.ARAP(V, F, [0, 0])
    # A zero-area face (vertex 4 halfway between 0 and 1): original ARAP's cotangents are not finite. (A fin,
    # a third face on an edge, is no error any more: ARAP sums the cotangents of all faces of the edge.)
    with pytest.raises(iarap.TopologyError, match="face 4 is degenerate"):
        iarap.ARAP(np.vstack([V, [[1, 0, 0]]]), np.vstack([F, [[0, 1, 4]]]), FIXED, method="arap")


def test_solver_still_works_after_errors():
    s = solver()
    for bad in [V[:3], np.full((2, 3), np.nan)]:
        with pytest.raises(ValueError):
            s.solve(bad)
    U = s.solve(V[FIXED], iterations=3)
    np.testing.assert_allclose(U, V, atol=1e-12)


def test_arguments_are_bound_as_python_binds_them():
    """ARAP.solve and Simulation take keywords assembled from the solve options' schema; wrong calls are
    TypeErrors in Python's words, naming the argument."""
    s = solver()
    for call, message in [
        (lambda: s.solve(V[FIXED], bogus=1), r"solve\(\) got an unexpected keyword argument 'bogus'"),
        (lambda: s.solve(V[FIXED], None, 3, -1, "newton"), r"solve\(\) takes at most 4 positional arguments"),
        (lambda: s.solve(V[FIXED], None, 3, iterations=4), r"solve\(\) got multiple values for argument 'iterations'"),
        (lambda: s.solve(), r"solve\(\) missing required argument 'targets'"),
        (lambda: iarap.Simulation(V, F, FIXED), r"__init__\(\) missing required argument 'dt'"),
        (lambda: iarap.Simulation(V, F, FIXED, dt="0.1"), r"__init__\(\) argument 'dt' must be float, got str"),
    ]:
        with pytest.raises(TypeError, match=message):
            call()
    U = s.solve(V[FIXED], None, 3, -1)  # iterations and tolerance still by position
    assert s.report["iterations"] == 3 and U.shape == V.shape
