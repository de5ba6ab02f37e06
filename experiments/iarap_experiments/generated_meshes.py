"""Meshes the report generates itself (written as OBJ with full double precision).

- flipped_lattice: Table 2's family. A flat equilateral triangular lattice (every interior edge Delaunay,
  opposite angles 60 + 60 degrees) in which a chosen fraction of the edges of ONE direction are flipped.
  Every triangle has exactly one edge of each direction, so flipped edges never share a triangle: each flip
  turns a pair of equilateral triangles into two 30-30-120 triangles, makes the new edge non-Delaunay and
  leaves all other edges Delaunay. The intrinsic Delaunay triangulation is therefore the original lattice,
  and each flipped edge is crossed by exactly one intrinsic edge that is traced as 2 segments: the ratio
  of segments to intrinsic edges is 1 + flips / edges, from 1.0 (no flip) to about 4/3 (all flipped), at a
  fixed vertex and edge count.
- stool: a symmetric stool-like solid (a seat on four legs) built from axis-aligned boxes on a regular
  lattice and triangulated by splitting every boundary quad along the SAME diagonal, so the surface is
  mirror-symmetric in x but its triangulation is not (the mirror image of a diagonal is the other one).
  The legs splay (x is scaled by a factor growing towards the floor), which keeps every face planar and
  the mesh mirror-symmetric but turns the side faces' rectangles into non-cyclic trapezoids, so one
  diagonal in two is (slightly) non-Delaunay.
- balloon: paper Fig. 12, a balloon-like surface of revolution (a teardrop, wider at the top, with a small
  knot at the bottom) as latitude-longitude rings, every quad split along the diagonal of the same index
  order. Quads between two rings are isosceles trapezoids, hence cyclic: both diagonals have cotan weight 0,
  the mesh is Delaunay (up to round-off) and mirror-symmetric in x and z while its triangulation is not.
- diagonal_grid: paper Fig. 1, a flat square grid with every square split along the same diagonal
  (Delaunay: squares are cyclic, the diagonals get weight 0), symmetric geometry, asymmetric triangulation.
"""
from __future__ import annotations

import numpy as np


def _quad_grid_faces(rows: int, cols: int) -> np.ndarray:
    """Faces of a rows x cols vertex grid (vertex r * cols + c at x = r, y = c), each cell split along
    (r,c)-(r+1,c+1), counter-clockwise seen from +z."""
    r, c = np.meshgrid(np.arange(rows - 1), np.arange(cols - 1), indexing="ij")
    a = (r * cols + c).ravel()
    b, d, e = a + 1, a + cols, a + cols + 1
    return np.vstack([np.stack([a, e, b], axis=1), np.stack([a, d, e], axis=1)])


def diagonal_grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    """An n x n vertex unit-spacing square grid in the xy plane centred at the origin, z = 0."""
    x = np.arange(n, dtype=np.float64) - (n - 1) / 2.0
    X, Y = np.meshgrid(x, x, indexing="ij")  # vertex r * n + c has x = x[r], y = x[c]
    V = np.stack([X.ravel(), Y.ravel(), np.zeros(n * n)], axis=1)
    return V, _quad_grid_faces(n, n)


def triangular_lattice(rows: int, cols: int) -> tuple[np.ndarray, np.ndarray]:
    """Equilateral lattice: row r shifted by r/2, height sqrt(3)/2; cells split along one lattice direction.

    Vertex r * cols + c sits at (c + r/2, r sqrt(3)/2, 0) (a parallelogram patch). With that layout the
    cell diagonal (r,c+1)-(r+1,c) is the short one (length 1), so every triangle is equilateral.
    """
    r, c = np.meshgrid(np.arange(rows), np.arange(cols), indexing="ij")
    V = np.stack([(c + 0.5 * r).ravel().astype(np.float64), (r * np.sqrt(3) / 2).ravel(), np.zeros(rows * cols)],
                 axis=1)
    rr, cc = np.meshgrid(np.arange(rows - 1), np.arange(cols - 1), indexing="ij")
    a = (rr * cols + cc).ravel()
    b, d, e = a + 1, a + cols, a + cols + 1
    # a=(r,c) b=(r,c+1) d=(r+1,c) e=(r+1,c+1); short diagonal b-d.
    F = np.vstack([np.stack([a, b, d], axis=1), np.stack([b, e, d], axis=1)])
    return V, F


def flipped_lattice(rows: int, cols: int, fraction: float, seed: int = 0) -> tuple[np.ndarray, np.ndarray, int]:
    """triangular_lattice with `fraction` of its short cell diagonals b-d flipped to the long one a-e.

    Returns V, F and the number of flipped edges. The flipped cells are drawn at random (seeded) so the
    non-Delaunay edges spread evenly.
    """
    V, F = triangular_lattice(rows, cols)
    cells = (rows - 1) * (cols - 1)
    rng = np.random.default_rng(seed)
    flipped = rng.permutation(cells)[: int(round(fraction * cells))]
    lower, upper = F[:cells].copy(), F[cells:].copy()
    a, b, d = lower[flipped, 0], lower[flipped, 1], lower[flipped, 2]
    e = upper[flipped, 1]
    lower[flipped] = np.stack([a, b, e], axis=1)  # same orientation (counter-clockwise) as before
    upper[flipped] = np.stack([a, e, d], axis=1)
    return V, np.vstack([lower, upper]), len(flipped)


def _box_union_surface(occupied: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Boundary of a union of unit voxels (occupied[i, j, k] for the cube [i, i+1] x [j, j+1] x [k, k+1]),
    as triangles with outward orientation, every quad split along the diagonal from its lowest corner
    (in lexicographic lattice order) to the opposite one. Assumes no two voxels touch only along an edge.
    """
    padded = np.pad(occupied, 1)
    quads = []
    for axis in range(3):
        for sign in (-1, 1):
            neighbour = np.roll(padded, -sign, axis=axis)
            faces = np.argwhere(padded & ~neighbour) - 1  # voxel indices with an exposed face on this side
            for i, j, k in faces:
                base = np.array([i, j, k])
                if sign > 0:
                    base[axis] += 1
                u, w = [ax for ax in range(3) if ax != axis]
                du, dw = np.eye(3, dtype=int)[u], np.eye(3, dtype=int)[w]
                corners = [base, base + du, base + du + dw, base + dw]
                # Counter-clockwise seen from outside: (du x dw) must point along the outward sign * e_axis.
                if sign * np.cross(du, dw)[axis] < 0:
                    corners = corners[::-1]
                quads.append(corners)
    quads = np.array(quads)  # q x 4 x 3 lattice points
    points, inverse = np.unique(quads.reshape(-1, 3), axis=0, return_inverse=True)
    Q = inverse.reshape(-1, 4)
    # Split along the diagonal through the lexicographically smallest corner: a fixed rule in lattice
    # coordinates, so the mirror image (x -> -x) of a diagonal is generally the other diagonal.
    triangles = []
    for q, quad in zip(Q, quads):
        start = min(range(4), key=lambda m: tuple(quad[m]))
        a, b, c, d = (q[(start + m) % 4] for m in range(4))
        triangles += [[a, b, c], [a, c, d]]
    return points.astype(np.float64), np.array(triangles, dtype=np.int64)


def stool(cells: int = 2, splay: float = 0.35) -> tuple[np.ndarray, np.ndarray, dict]:
    """Stool-like closed solid, mirror-symmetric in x and z; returns V, F and named vertex sets.

    `cells` lattice cells per leg width. In lattice units: seat W x T x W with W = 7 * cells and
    T = 2 * cells, four legs cells x cells wide and H = 5 * cells tall at the corners. Then x and z are
    centred, x is scaled by (1 + splay * (1 - y / H)) below the seat and everything by 1 / W.
    """
    W, T, H, L = 7 * cells, 2 * cells, 5 * cells, cells
    occupied = np.zeros((W, H + T, W), dtype=bool)
    occupied[:, H:, :] = True
    for x0 in (0, W - L):
        for z0 in (0, W - L):
            occupied[x0:x0 + L, :H, z0:z0 + L] = True
    V, F = _box_union_surface(occupied)
    V[:, 0] -= W / 2.0
    V[:, 2] -= W / 2.0
    below = V[:, 1] < H
    V[below, 0] *= 1.0 + splay * (1.0 - V[below, 1] / H)
    V /= float(W)  # unit seat width
    sets = {"feet": np.where(V[:, 1] <= 0.0)[0], "seat_top": np.where(V[:, 1] >= (H + T) / float(W) - 1e-12)[0]}
    return V, F, sets


def balloon(longitudes: int = 48, latitudes: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Closed balloon-like surface of revolution about y (height 2.4, max radius ~1.1); `longitudes` even
    so that x -> -x maps vertices to vertices. Vertex 0 is the top pole, the last one the bottom pole."""
    assert longitudes % 2 == 0
    phi = np.pi * np.arange(1, latitudes) / latitudes  # polar angle of each ring, 0 at the top
    knot = 0.12 * np.exp(-(((np.pi - phi) - 0.22) / 0.07) ** 2)  # a small bulge near the bottom pole
    radius = np.sin(phi) * (1.0 + 0.3 * np.cos(phi)) + knot
    height = 1.2 * np.cos(phi)
    theta = 2.0 * np.pi * np.arange(longitudes) / longitudes
    rings = np.stack([np.outer(radius, np.cos(theta)), np.repeat(height[:, None], longitudes, axis=1),
                      np.outer(radius, np.sin(theta))], axis=2).reshape(-1, 3)
    V = np.vstack([[0.0, 1.2, 0.0], rings, [0.0, -1.2, 0.0]])
    bottom = len(V) - 1
    ring = lambda r, j: 1 + r * longitudes + j % longitudes  # noqa: E731
    F = [[0, ring(0, j + 1), ring(0, j)] for j in range(longitudes)]
    for r in range(latitudes - 2):
        for j in range(longitudes):
            a, b, c, d = ring(r, j), ring(r, j + 1), ring(r + 1, j), ring(r + 1, j + 1)
            F += [[a, b, d], [a, d, c]]  # outward: theta runs from x towards z, rings downwards
    F += [[bottom, ring(latitudes - 2, j), ring(latitudes - 2, j + 1)] for j in range(longitudes)]
    return V, np.array(F, dtype=np.int64)
