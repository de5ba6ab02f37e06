"""Step-by-step numerical check of the proof in docs/operator-identity.md, independent of the library.

On a flat mesh the intrinsic triangulations are planar straight-line triangulations of the same points
(the intrinsic Delaunay one is the planar Delaunay triangulation, reached by Lawson flips), so every
quantity of the proof can be computed with numpy alone: segments by clipping straight edges against the
input triangles, the function h from circumcentres, boundary integrals by exact quadrature.
Round-off: every quantity is a sum of O(100) terms of size O(1) (unit square, O(1) cotangents), so the
checks use 1e-10 absolute on quantities of order 1-100.
"""
from __future__ import annotations

import numpy as np
import pytest

TOL = 1e-10


def grid(n: int, jitter: float, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(n+1)^2 points of the unit square, interior ones jittered, squares split along one diagonal."""
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 1.0, n + 1)
    X, Y = np.meshgrid(x, x, indexing="xy")
    V = np.stack([X.ravel(), Y.ravel()], axis=1)
    interior = (V[:, 0] > 0) & (V[:, 0] < 1) & (V[:, 1] > 0) & (V[:, 1] < 1)
    V[interior] += jitter / n * rng.uniform(-1, 1, size=(interior.sum(), 2))
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 1, a + n + 2
            F += [[a, b, d], [a, d, c]]
    return V, np.array(F)


def cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def cot_at(V, o, a, b) -> float:
    """Cotangent of the angle at o in triangle (o, a, b)."""
    u, w = V[a] - V[o], V[b] - V[o]
    return float(u @ w / abs(cross(V[o], V[a], V[b])))


def edge_map(F) -> dict:
    """Undirected edge -> list of (face, corner opposite the edge)."""
    edges: dict = {}
    for f, tri in enumerate(F):
        for k in range(3):
            i, j = tri[(k + 1) % 3], tri[(k + 2) % 3]
            edges.setdefault((min(i, j), max(i, j)), []).append((f, k))
    return edges


def flip(V, F, edge, faces) -> bool:
    """Flips an interior edge whose quad is strictly convex; keeps counter-clockwise orientation."""
    (f0, k0), (f1, k1) = faces
    c, d = F[f0][k0], F[f1][k1]
    a, b = F[f0][(k0 + 1) % 3], F[f0][(k0 + 2) % 3]  # f0 = (c, a, b) counter-clockwise
    if cross(V[c], V[d], V[a]) * cross(V[c], V[d], V[b]) >= 0 or cross(V[a], V[b], V[c]) * cross(V[a], V[b], V[d]) >= 0:
        return False
    if min(abs(cross(V[c], V[a], V[d])), abs(cross(V[d], V[b], V[c]))) < 1e-6:
        return False
    F[f0] = [c, a, d]
    F[f1] = [d, b, c]
    return True


def random_flips(V, F, count: int, seed: int) -> np.ndarray:
    F = F.copy()
    rng = np.random.default_rng(seed)
    done = 0
    for _ in range(50 * count):
        if done == count:
            break
        edges = [(e, fs) for e, fs in edge_map(F).items() if len(fs) == 2]
        e, fs = edges[rng.integers(len(edges))]
        done += flip(V, F, e, fs)
    return F


def lawson(V, F) -> np.ndarray:
    """Planar Delaunay triangulation of the same points by flipping (Lawson)."""
    F = F.copy()
    while True:
        flipped = False
        for (i, j), fs in edge_map(F).items():
            if len(fs) == 2:
                (f0, k0), (f1, k1) = fs
                if cot_at(V, F[f0][k0], i, j) + cot_at(V, F[f1][k1], i, j) < -1e-12 and flip(V, F, (i, j), fs):
                    flipped = True
                    break
        if not flipped:
            return F


def dual_lengths(V, F) -> dict:
    """|*e| = w_e l_e for every undirected edge, w_e = (cot a + cot b) / 2 (one term on the boundary)."""
    out = {}
    for (i, j), fs in edge_map(F).items():
        w = sum(cot_at(V, F[f][k], i, j) for f, k in fs) / 2
        out[(i, j)] = w * np.linalg.norm(V[j] - V[i])
    return out


def cotan_laplacian(V, F) -> np.ndarray:
    L = np.zeros((len(V), len(V)))
    for (i, j), star in dual_lengths(V, F).items():
        w = star / np.linalg.norm(V[j] - V[i])
        L[i, j] -= w
        L[j, i] -= w
        L[i, i] += w
        L[j, j] += w
    return L


def barycentric(V, tri, x) -> np.ndarray:
    a, b, c = V[tri]
    area = cross(a, b, c)
    return np.array([cross(x, b, c), cross(a, x, c), cross(a, b, x)]) / area


def clip(V, tri, p, q) -> tuple[float, float] | None:
    """Parameter interval of the segment p + s (q - p), s in [0, 1], inside the closed triangle."""
    lo, hi = 0.0, 1.0
    for k in range(3):
        a, b = V[tri[k]], V[tri[(k + 1) % 3]]
        fp, fq = cross(a, b, p), cross(a, b, q)  # >= 0 inside (counter-clockwise)
        if fp < 0 and fq < 0:
            return None
        if fp < 0:
            lo = max(lo, fp / (fp - fq))
        elif fq < 0:
            hi = min(hi, fp / (fp - fq))
    return (lo, hi) if hi - lo > 1e-12 else None


def segments(V, F, Fi) -> list[dict]:
    """Segments of the intrinsic edges of Fi over the input triangles F (Eq. 7, 8, 11)."""
    input_edges = edge_map(F)
    out = []
    for (i, j), star in dual_lengths(V, Fi).items():
        p, q = V[i], V[j]
        length = np.linalg.norm(q - p)
        if (i, j) in input_edges:  # an input edge: one segment, b = e_j - e_i (either face)
            f = input_edges[(i, j)][0][0]
            pieces = [(f, 0.0, 1.0)]
        else:
            pieces = [(f, *iv) for f in range(len(F)) if (iv := clip(V, F[f], p, q))]
        for f, s0, s1 in pieces:
            b = np.zeros(len(V))
            x0, x1 = p + s0 * (q - p), p + s1 * (q - p)
            b[F[f]] += barycentric(V, F[f], x1) - barycentric(V, F[f], x0)
            out.append({"edge": (i, j), "face": f, "b": b, "len": (s1 - s0) * length, "star": star,
                        "tau": (q - p) / length, "on_input_edge": (i, j) in input_edges})
        assert abs(sum((s1 - s0) for _, s0, s1 in pieces) - 1.0) < 1e-12  # the segments tile the edge
    return out


def circumcentre(V, tri) -> np.ndarray:
    a, b, c = V[tri]
    d = 2 * cross(a, b, c)
    A, B, C = a @ a, b @ b, c @ c
    return np.array([A * (b[1] - c[1]) + B * (c[1] - a[1]) + C * (a[1] - b[1]),
                     A * (c[0] - b[0]) + B * (a[0] - c[0]) + C * (b[0] - a[0])]) / d


def locate(V, Fi, x) -> int:
    for f, tri in enumerate(Fi):
        if barycentric(V, tri, x).min() > -1e-12:
            return f
    raise AssertionError(f"point {x} outside the mesh")


def gradient(V, tri, u) -> np.ndarray:
    a, b, c = V[tri]
    M = np.array([b - a, c - a])
    return np.linalg.solve(M, np.array([u[tri[1]] - u[tri[0]], u[tri[2]] - u[tri[0]]]))


def boundary_integral(V, F, Fi, f, u) -> float:
    """∮_{∂t} ν^T A ∇h|_t dℓ for input triangle f, A = |g|^2 Id - g g^T: split each side where intrinsic
    edges cross it (∇h is affine between crossings), midpoint rule per piece (exact for affine integrands)."""
    tri = F[f]
    g = gradient(V, tri, u)
    A = (g @ g) * np.eye(2) - np.outer(g, g)
    centres = [circumcentre(V, t) for t in Fi]
    total = 0.0
    for k in range(3):
        a, b = V[tri[k]], V[tri[(k + 1) % 3]]
        side = b - a
        length = np.linalg.norm(side)
        nu = np.array([side[1], -side[0]]) / length  # outward for a counter-clockwise triangle
        cuts = {0.0, 1.0}
        for (i, j) in dual_lengths(V, Fi):
            p, q = V[i], V[j]
            den = cross(np.zeros(2), side, q - p)
            if abs(den) > 1e-14:
                s = cross(np.zeros(2), p - a, q - p) / den
                r = cross(np.zeros(2), p - a, side) / den
                if 1e-9 < s < 1 - 1e-9 and 0 <= r <= 1:  # crossings inside the side
                    cuts.add(float(s))
        cuts = sorted(cuts)
        for s0, s1 in zip(cuts, cuts[1:]):
            x = a + 0.5 * (s0 + s1) * side
            inside = x - 1e-9 * nu  # the intrinsic triangle on t's side of the boundary
            c = centres[locate(V, Fi, inside)]
            total += (nu @ A @ (c - x)) * (s1 - s0) * length
    return total


@pytest.fixture(params=["delaunay", "non-delaunay"])
def meshes(request):
    V, F0 = grid(5, 0.3, seed=4)
    F = random_flips(V, F0, 25, seed=2)  # the input: far from Delaunay
    Fi = lawson(V, F) if request.param == "delaunay" else random_flips(V, F0, 25, seed=9)
    negative = sum(d < -1e-9 for d in dual_lengths(V, Fi).values())
    # The intrinsic triangulation is Delaunay, or has negative dual lengths that the proof must handle.
    assert (negative == 0) == (request.param == "delaunay"), negative
    assert sum(d < -1e-9 for d in dual_lengths(V, F).values()) > 0  # the input is not Delaunay
    return V, F, Fi


def test_jump_of_grad_h_is_dual_length(meshes):
    """(d): c_2 - c_1 = |*e| n, n the unit normal from τ1 to τ2; (e): ∂_ν h = -|*e| on boundary edges."""
    V, _, Fi = meshes
    star = dual_lengths(V, Fi)
    for (i, j), fs in edge_map(Fi).items():
        t = V[j] - V[i]
        n = np.array([t[1], -t[0]]) / np.linalg.norm(t)
        if len(fs) == 2:
            (f1, _), (f2, _) = fs
            c1, c2 = circumcentre(V, Fi[f1]), circumcentre(V, Fi[f2])
            if (V[Fi[f2]].mean(0) - V[i]) @ n < 0:
                n = -n  # from f1 into f2
            assert np.allclose(c2 - c1, star[(i, j)] * n, atol=TOL)
        else:
            (f, _), = fs
            if (V[Fi[f]].mean(0) - V[i]) @ n > 0:
                n = -n  # outward
            x = 0.5 * (V[i] + V[j])
            assert abs((circumcentre(V, Fi[f]) - x) @ n + star[(i, j)]) < TOL


def test_segment_terms_and_per_triangle_identity(meshes):
    """(1) per segment, (2) per input triangle, the boundary sum of Section 5, and the theorem."""
    V, F, Fi = meshes
    u = np.random.default_rng(5).normal(size=len(V))
    segs = segments(V, F, Fi)
    grads = [gradient(V, t, u) for t in F]
    # (1): w_s (b_s . u)^2 = |*e| |s| (∂_τ u)^2 with w_s = |*e| / |s|.
    for s in segs:
        g = grads[s["face"]]
        assert abs(s["star"] / s["len"] * (s["b"] @ u) ** 2 - s["star"] * s["len"] * (g @ s["tau"]) ** 2) < TOL
    # (2) for every input triangle.
    boundary = []
    for f, tri in enumerate(F):
        g = grads[f]
        area = 0.5 * cross(*V[tri])
        interior = sum(s["star"] * s["len"] * (g @ s["tau"]) ** 2 for s in segs
                       if s["face"] == f and not s["on_input_edge"])
        boundary.append(boundary_integral(V, F, Fi, f, u))
        assert abs(area * (g @ g) - (interior - boundary[-1])) < TOL, f"triangle {f}"
    # Section 5: the boundary integrals sum to minus the terms of the intrinsic edges on input edges.
    on_edges = sum(s["star"] * s["len"] * (grads[s["face"]] @ s["tau"]) ** 2 for s in segs if s["on_input_edge"])
    assert abs(sum(boundary) + on_edges) < TOL
    # The theorem: sum_s w_s b_s b_s^T = L_cot of the input.
    L = sum(s["star"] / s["len"] * np.outer(s["b"], s["b"]) for s in segs)
    assert np.abs(L - cotan_laplacian(V, F)).max() < TOL
    # ... and not the cotan Laplacian of the intrinsic triangulation (the check is not vacuous).
    assert np.abs(cotan_laplacian(V, Fi) - cotan_laplacian(V, F)).max() > 0.1
