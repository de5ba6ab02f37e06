"""Returned arrays own their memory: they outlive the solver and never alias its state."""
import gc

import numpy as np

import iarap
from conftest import REPO, handle_scene


def owns(array):
    """The memory belongs to numpy: the array or the arrays it views (scipy keeps views of what it gets),
    never a capsule or buffer kept alive from C++."""
    while array.base is not None:
        if not isinstance(array.base, np.ndarray):
            return False
        array = array.base
    return array.flags.owndata


def test_solver_outputs_own_their_memory(bunny):
    V, F = bunny
    fixed, targets = handle_scene(V)
    solver = iarap.ARAP(V, F, fixed=fixed, method="iarap")
    U = solver.solve(targets, iterations=5)
    report, R, L, pinned, fixed_out = solver.report, solver.rotations, solver.system_matrix(), solver.pinned, solver.fixed
    copies = [U.copy(), report["energies"].copy(), R.copy(), L.data.copy(), fixed_out.copy()]
    for array in [U, report["energies"], report["local_ms_per_iteration"], R, pinned, fixed_out, L.data, L.indices,
                  L.indptr]:
        assert owns(array)
    del solver
    gc.collect()
    # Fresh allocations of the same sizes would land on freed solver memory if the arrays were views into it.
    clutter = [iarap.ARAP(V, F, fixed=fixed, method="iarap").solve(targets * 2, iterations=5) for _ in range(2)]
    for array, copy in zip([U, report["energies"], R, L.data, fixed_out], copies):
        np.testing.assert_array_equal(array, copy)
    U[:] = 0  # writable, and writing it touches nothing else
    assert len(clutter) == 2


def test_modifying_outputs_does_not_change_the_solver(bunny):
    V, F = bunny
    fixed, targets = handle_scene(V)
    solver = iarap.ARAP(V, F, fixed=fixed)
    U = solver.solve(targets, iterations=5)
    expected = U.copy()
    U[:] = np.nan
    solver.fixed[:] = 0
    solver.rotations[:] = 0
    np.testing.assert_array_equal(solver.solve(targets, iterations=5), expected)


def test_mesh_and_intrinsic_outputs_own_their_memory(bunny):
    V, F = bunny
    V2, F2 = iarap.read_mesh(REPO / "data" / "bunny.off")
    assert owns(V2) and owns(F2)
    idt = iarap.intrinsic_delaunay(V, F)
    for key in ["F", "E", "length", "cot_weight", "corner_angle"]:
        assert owns(idt[key]), key
    for key, array in idt["segments"].items():
        assert owns(array), key
    assert owns(idt["B"].data) and owns(idt["B"].indices)
    L = iarap.laplacian(V, F)
    assert owns(L.data) and owns(L.indptr)
