"""Geometric measures of deformed meshes: mirror symmetry, flatness, rigidity of a region."""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree


class AsymmetricRestShape(ValueError):
    """The rest vertex set is not mirror-symmetric, so a symmetry error would be meaningless."""


def mirror_map(V: np.ndarray, axis: int, center: float, tolerance: float) -> np.ndarray:
    """sigma with V[sigma[i]] = mirror(V[i]) about the plane {x_axis = center}, matched within tolerance.

    Raises AsymmetricRestShape naming the worst vertex when some mirror image is not a vertex.
    """
    mirrored = V.copy()
    mirrored[:, axis] = 2.0 * center - mirrored[:, axis]
    distance, sigma = cKDTree(V).query(mirrored)
    worst = int(np.argmax(distance))
    if distance[worst] > tolerance:
        raise AsymmetricRestShape(f"vertex {worst} has no mirror image (nearest at {distance[worst]:.3g} > "
                                  f"{tolerance:.3g})")
    return sigma


def symmetry_error(U: np.ndarray, sigma: np.ndarray, axis: int, center: float) -> float:
    """max_i |mirror(U_i) - U_sigma(i)|: distance between the deformed mesh and its mirror image
    (vertex-wise through the rest shape's mirror correspondence)."""
    mirrored = U.copy()
    mirrored[:, axis] = 2.0 * center - mirrored[:, axis]
    return float(np.linalg.norm(mirrored - U[sigma], axis=1).max())


def plane_distance_max(P: np.ndarray) -> float:
    """Max distance of the points P (n x 3) to their least-squares plane."""
    centred = P - P.mean(axis=0)
    normal = np.linalg.svd(centred, full_matrices=False)[2][2]
    return float(np.abs(centred @ normal).max())


def best_rotation(P: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """The rotation R of the least-squares rigid motion q = R (p - p0) + q0 (Kabsch)."""
    p0, q0 = P.mean(axis=0), Q.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - p0).T @ (Q - q0))
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
    return (U @ D @ Vt).T


def rigid_residual_max(P: np.ndarray, Q: np.ndarray) -> float:
    """Max distance between Q and the best rigid motion of P (Kabsch, least squares): how much a region
    bent or stretched, independent of where it moved."""
    p0, q0 = P.mean(axis=0), Q.mean(axis=0)
    R = best_rotation(P, Q)
    return float(np.linalg.norm((P - p0) @ R.T + q0 - Q, axis=1).max())


def rotation_degrees(P: np.ndarray, Q: np.ndarray) -> float:
    """Angle of the best-fit rotation taking P to Q (degrees): how much the whole shape turned."""
    R = best_rotation(P, Q)
    return float(np.degrees(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0))))
