# Type stubs of the iarap package (the extension iarap._core, re-exported). Checked against the built
# module by python/tests/test_stubs.py (mypy.stubtest, plus parameter names, kinds and defaults).
import os
from collections.abc import Sequence
from typing import Any, Literal, overload

import numpy as np
import numpy.typing as npt
import scipy.sparse

__version__: str

_FloatArray = npt.NDArray[np.float64]
_IndexArray = npt.NDArray[np.int64]
_StrPath = str | bytes | os.PathLike[str] | os.PathLike[bytes]

ARAP_METHODS: tuple[str, ...]
LAPLACIAN_KINDS: tuple[str, ...]
MASS_KINDS: tuple[str, ...]
SOLVE_OPTIONS: tuple[dict[str, Any], ...]

class Error(Exception): ...
class InputError(Error, ValueError): ...
class TopologyError(Error, ValueError): ...
class SolverError(Error, RuntimeError): ...

def read_mesh(path: _StrPath) -> tuple[_FloatArray, _IndexArray]: ...
def write_mesh(path: _StrPath, V: npt.ArrayLike, F: npt.ArrayLike) -> None: ...
def check_mesh(V: npt.ArrayLike, F: npt.ArrayLike) -> dict[str, Any]: ...
def repair_mesh(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    *,
    weld_tolerance: float = 1e-12,
    split_open_fans: bool = False,
) -> tuple[_FloatArray, _IndexArray, _IndexArray, dict[str, Any]]: ...
def read_tet_mesh(path: _StrPath) -> tuple[_FloatArray, _IndexArray]: ...
def write_tet_mesh(path: _StrPath, V: npt.ArrayLike, T: npt.ArrayLike) -> None: ...
def tet_boundary_faces(T: npt.ArrayLike) -> _IndexArray: ...

class ARAP:
    def __init__(
        self,
        V: npt.ArrayLike,
        F: npt.ArrayLike,
        fixed: npt.ArrayLike,
        method: str = "iarap",
        *,
        pin_unconstrained_components: bool = False,
        refine_boundary: bool = True,
        soft_vertices: npt.ArrayLike | None = None,
        soft_weights: npt.ArrayLike | None = None,
        soft_faces: npt.ArrayLike | None = None,
        soft_barycentric: npt.ArrayLike | None = None,
        soft_face_weights: npt.ArrayLike | None = None,
        hard_faces: npt.ArrayLike | None = None,
        hard_barycentric: npt.ArrayLike | None = None,
        stiffness: npt.ArrayLike | None = None,
        rigid_groups: Sequence[Sequence[int]] | None = None,
    ) -> None: ...
    def solve(
        self,
        targets: npt.ArrayLike,
        U0: npt.ArrayLike | None = None,
        iterations: int = 50,
        tolerance: float = 1e-06,
        *,
        accelerator: str = "newton",
        window: int = 8,
        gradient_tolerance: float = 0.0,
        time_budget_ms: float = 0.0,
        newton_trust_radius: float = 0.0,
        rotation_smoothing: float = 0.0,
        soft_targets: npt.ArrayLike | None = None,
        forces: npt.ArrayLike | None = None,
    ) -> _FloatArray: ...
    def set_soft_weights(
        self, soft_weights: npt.ArrayLike | None, soft_face_weights: npt.ArrayLike | None = None
    ) -> None: ...
    def penalty(self, U: npt.ArrayLike, soft_targets: npt.ArrayLike) -> float: ...
    @property
    def fixed(self) -> _IndexArray: ...
    @fixed.setter
    def fixed(self, fixed: npt.ArrayLike) -> None: ...
    @property
    def report(self) -> dict[str, Any] | None: ...
    @property
    def rotations(self) -> _FloatArray: ...
    @property
    def method(self) -> str: ...
    @property
    def factorization(self) -> str: ...
    @property
    def factorizations(self) -> int: ...
    @property
    def pinned(self) -> _IndexArray: ...
    @property
    def min_weight(self) -> float: ...
    @property
    def intrinsic(self) -> dict[str, Any]: ...
    def energy(self, U: npt.ArrayLike) -> float: ...
    def cell_energy(self, U: npt.ArrayLike) -> _FloatArray: ...
    def gradient(self, U: npt.ArrayLike) -> _FloatArray: ...
    def system_matrix(self) -> scipy.sparse.csr_matrix: ...

@overload
def laplacian(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    kind: str = "cotan",
    *,
    return_mass: Literal[False] = False,
    mass: str | None = None,
) -> scipy.sparse.csr_matrix: ...
@overload
def laplacian(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    kind: str = "cotan",
    *,
    return_mass: Literal[True],
    mass: str | None = None,
) -> tuple[scipy.sparse.csr_matrix, scipy.sparse.csr_matrix]: ...
def mass_matrix(V: npt.ArrayLike, F: npt.ArrayLike, kind: str = "voronoi") -> scipy.sparse.csr_matrix: ...
def intrinsic_delaunay(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    *,
    delaunay_tolerance: float = 1e-12,
    mollify: bool = True,
    mollify_epsilon: float = 1e-06,
    refine_boundary: bool = False,
    max_boundary_insertions: int = -1,
) -> dict[str, Any]: ...
# One chart (a disk): parameterize, one UV per vertex. Any mesh: uv_atlas, one UV per corner and a chart per
# face; parameterize's TopologyError for a non-disk names uv_atlas.
def parameterize(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    *,
    energy: str = "triangle",
    init: str | None = None,
    boundary: str = "free",
    allow_flips: bool = False,
    pins: npt.ArrayLike | None = None,
    pin_uv: npt.ArrayLike | None = None,
    iterations: int = 100,
    tolerance: float = 1e-06,
    accelerator: str = "newton",
    window: int = 8,
    gradient_tolerance: float = 0.0,
    time_budget_ms: float = 0.0,
    newton_trust_radius: float = 0.0,
    rotation_smoothing: float = 0.0,
) -> tuple[_FloatArray, dict[str, Any]]: ...
def uv_atlas(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    *,
    energy: str = "triangle",
    allow_flips: bool = False,
    texture_size: int = 1024,
    padding: float = 2.0,
    max_angle: float = 60.0,
    target_distortion: float = 0.05,
    min_chart_faces: int = 16,
    iterations: int = 100,
    tolerance: float = 0.0001,
    accelerator: str = "newton",
    window: int = 8,
    gradient_tolerance: float = 0.0,
    time_budget_ms: float = 0.0,
    newton_trust_radius: float = 0.0,
    rotation_smoothing: float = 0.0,
) -> tuple[_FloatArray, _IndexArray, dict[str, Any]]: ...
def deform_file(
    mesh: _StrPath,
    *,
    scenario: _StrPath | None = None,
    constraints: _StrPath | None = None,
    method: str = "iarap",
    refine_boundary: bool = True,
    repair: bool = False,
    keep_numbering: bool = False,
    pin_unconstrained_components: bool = False,
    gravity: npt.ArrayLike | None = None,
    density: float = 1.0,
    forces: _StrPath | None = None,
    stiffness: _StrPath | None = None,
    rigid: _StrPath | None = None,
    volume: bool = False,
    iterations: int = 50,
    tolerance: float = 1e-06,
    accelerator: str = "newton",
    window: int = 8,
    gradient_tolerance: float = 0.0,
    time_budget_ms: float = 0.0,
    newton_trust_radius: float = 0.0,
    rotation_smoothing: float = 0.0,
) -> tuple[_FloatArray, _IndexArray, dict[str, Any]]: ...
def register(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    target_points: npt.ArrayLike,
    *,
    target_normals: npt.ArrayLike | None = None,
    target_faces: npt.ArrayLike | None = None,
    landmarks: npt.ArrayLike | None = None,
    landmark_targets: npt.ArrayLike | None = None,
    landmark_weight: float = 100.0,
    method: str = "iarap",
    prealign: str = "rigid",
    stages: int = 8,
    rounds: int = 30,
    initial_weight: float = 0.02,
    final_weight: float = 1.0,
    point_to_plane: float = 0.95,
    backward_weight: float = 0.1,
    reject_distance: float = 3.0,
    reject_angle: float = 60.0,
    normal_neighbours: int = 12,
    iterations: int = 3,
    tolerance: float = 1e-05,
    accelerator: str = "none",
    window: int = 8,
    gradient_tolerance: float = 0.0,
    time_budget_ms: float = 0.0,
    newton_trust_radius: float = 0.0,
    rotation_smoothing: float = 0.0,
) -> tuple[_FloatArray, dict[str, Any]]: ...
def set_thread_count(n: int) -> None: ...
def thread_count() -> int: ...

def vertex_masses(V: npt.ArrayLike, F: npt.ArrayLike, method: str = "iarap", density: float = 1.0) -> _FloatArray: ...

class Simulation:
    def __init__(
        self,
        V: npt.ArrayLike,
        F: npt.ArrayLike,
        fixed: npt.ArrayLike | None = None,
        *,
        dt: float,
        method: str = "iarap",
        gravity: npt.ArrayLike = (0.0, 0.0, 0.0),
        damping: float = 0.0,
        density: float = 1.0,
        forces: npt.ArrayLike | None = None,
        refine_boundary: bool = True,
        iterations: int = 100,
        tolerance: float = 1e-10,
        accelerator: str = "newton",
        window: int = 8,
        gradient_tolerance: float = 0.0,
        time_budget_ms: float = 0.0,
        newton_trust_radius: float = 0.0,
        rotation_smoothing: float = 0.0,
    ) -> None: ...
    def step(self, targets: npt.ArrayLike | None = None) -> dict[str, Any]: ...
    @property
    def positions(self) -> _FloatArray: ...
    @property
    def velocities(self) -> _FloatArray: ...
    @velocities.setter
    def velocities(self, velocities: npt.ArrayLike) -> None: ...
    @property
    def masses(self) -> _FloatArray: ...
    @property
    def forces(self) -> _FloatArray: ...
    @property
    def momentum(self) -> _FloatArray: ...
    @property
    def kinetic_energy(self) -> float: ...
    @property
    def elastic_energy(self) -> float: ...
    @property
    def potential_energy(self) -> float: ...
    @property
    def time(self) -> float: ...
    @property
    def steps(self) -> int: ...
