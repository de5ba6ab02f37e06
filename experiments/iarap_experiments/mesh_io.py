"""Reading and writing the ASCII OFF and OBJ triangle meshes the experiments exchange with the CLI.

Only what the report needs: the CLI reads every format itself; Python reads the bundled/shared OFF and
OBJ meshes and the OFF files `iarap deform` writes, to measure symmetry, flatness and to render. Binary
PLY is read by the CLI only (the report asks it for numbers, never for vertices).
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np


class MeshFormatError(ValueError):
    """A mesh file this reader cannot use; the message names the file and line."""


@dataclass
class Mesh:
    V: np.ndarray  # #V x 3 float64 positions
    F: np.ndarray  # #F x 3 int64 triangles (0-based)


def _triangulate(polygon: list[int]) -> list[list[int]]:
    # Fan triangulation: the shared meshes' quads (halftunnel) are planar and convex.
    return [[polygon[0], polygon[k], polygon[k + 1]] for k in range(1, len(polygon) - 1)]


def read_off(path: str) -> Mesh:
    with open(path, encoding="ascii", errors="replace") as f:
        lines = [(n + 1, line.split("#", 1)[0].split()) for n, line in enumerate(f)]
    lines = [(n, tokens) for n, tokens in lines if tokens]
    if not lines or not lines[0][1][0].endswith("OFF"):
        raise MeshFormatError(f"{path}:1: not an OFF file (no OFF header)")
    header_tokens = lines[0][1][1:]
    body = lines[1:]
    if not header_tokens:
        header_tokens, body = body[0][1], body[1:]
    vertex_count, face_count = int(header_tokens[0]), int(header_tokens[1])
    if len(body) < vertex_count + face_count:
        raise MeshFormatError(f"{path}: header promises {vertex_count} vertices and {face_count} faces, "
                              f"file has {len(body)} data lines")
    V = np.array([[float(t) for t in tokens[:3]] for _, tokens in body[:vertex_count]], dtype=np.float64)
    faces: list[list[int]] = []
    for line_number, tokens in body[vertex_count:vertex_count + face_count]:
        n = int(tokens[0])
        polygon = [int(t) for t in tokens[1:1 + n]]
        if len(polygon) != n or n < 3 or min(polygon) < 0 or max(polygon) >= vertex_count:
            raise MeshFormatError(f"{path}:{line_number}: bad face {' '.join(tokens)} "
                                  f"(mesh has {vertex_count} vertices)")
        faces.extend(_triangulate(polygon))
    return Mesh(V, np.array(faces, dtype=np.int64).reshape(-1, 3))


def read_obj_elements(path: str) -> tuple[np.ndarray, list[list[int]], list[list[int]]]:
    """Vertices (#V x 3), polygons and polylines (`l` records) of an OBJ file, 0-based."""
    vertices: list[list[float]] = []
    polygons: list[list[int]] = []
    lines: list[list[int]] = []
    with open(path, encoding="ascii", errors="replace") as f:
        for line_number, line in enumerate(f, start=1):
            tokens = line.split()
            if not tokens or tokens[0] not in ("v", "f", "l"):
                continue
            if tokens[0] == "v":
                vertices.append([float(t) for t in tokens[1:4]])
                continue
            indices = []
            for t in tokens[1:]:
                index = int(t.split("/")[0])
                indices.append(index - 1 if index > 0 else len(vertices) + index)
            if len(indices) < (3 if tokens[0] == "f" else 2) or min(indices) < 0:
                raise MeshFormatError(f"{path}:{line_number}: bad element {line.strip()}")
            (polygons if tokens[0] == "f" else lines).append(indices)
    V = np.array(vertices, dtype=np.float64).reshape(-1, 3)
    used = [i for element in polygons + lines for i in element]
    if used and max(used) >= len(V):
        raise MeshFormatError(f"{path}: an element uses vertex {max(used)}; the file has {len(V)} vertices")
    return V, polygons, lines


def read_obj(path: str) -> Mesh:
    V, polygons, _ = read_obj_elements(path)
    faces = [triangle for polygon in polygons for triangle in _triangulate(polygon)]
    return Mesh(V, np.array(faces, dtype=np.int64).reshape(-1, 3))


def read_mesh(path: str) -> Mesh:
    extension = os.path.splitext(path)[1].lower()
    if extension == ".off":
        return read_off(path)
    if extension == ".obj":
        return read_obj(path)
    raise MeshFormatError(f"{path}: only .off and .obj are read in Python (convert with the CLI)")


def write_obj(path: str, V: np.ndarray, F: np.ndarray) -> None:
    """Writes an OBJ with full double precision (generated meshes must be symmetric to the last bit)."""
    with open(path, "w", encoding="ascii") as f:
        f.write("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V.tolist()))
        f.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F.tolist()))


def write_constraints(path: str, indices: np.ndarray, targets: np.ndarray) -> None:
    """The CLI's constraints file: `index x y z` per line (0-based index)."""
    with open(path, "w", encoding="ascii") as f:
        f.write("".join(f"{int(i)} {x!r} {y!r} {z!r}\n" for i, (x, y, z) in zip(indices, targets.tolist())))


def bbox_diagonal(V: np.ndarray) -> float:
    return float(np.linalg.norm(V.max(axis=0) - V.min(axis=0)))
