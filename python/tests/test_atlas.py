"""iarap.uv_atlas on meshes iarap.parameterize refuses: a closed bunny, a torus, a mesh of two pieces. Each
atlas is checked from its arrays (per-corner UVs, chart ids), not only from its report."""
import numpy as np
import pytest

import iarap
from conftest import icosphere


def torus(major_segments, minor_segments, major_radius=2.0, minor_radius=1.0):
    """A closed torus (genus 1) of major_segments x minor_segments quads, each split into two triangles,
    faces counter-clockwise seen from outside."""
    u, v = np.meshgrid(np.arange(major_segments), np.arange(minor_segments), indexing="ij")
    a, b = 2 * np.pi * u.ravel() / major_segments, 2 * np.pi * v.ravel() / minor_segments
    ring = major_radius + minor_radius * np.cos(b)
    V = np.column_stack([ring * np.cos(a), ring * np.sin(a), minor_radius * np.sin(b)])

    def index(i, j):
        return (i % major_segments) * minor_segments + j % minor_segments

    F = []
    for i in range(major_segments):
        for j in range(minor_segments):
            p, q, r, s = index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)
            F += [[p, q, r], [p, r, s]]
    return V, np.array(F)


def two_pieces():
    """A torus and, beside it, a sphere: two components of genus 1 and 0 in one mesh."""
    Vt, Ft = torus(32, 16)
    Vs, Fs = icosphere(2)
    return np.vstack([Vt, Vs + [5.0, 0.0, 0.0]]), np.vstack([Ft, Fs + len(Vt)]), len(Ft)


def triangle_areas(V, F):
    return 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)


def signed_uv_areas(corner_uv):
    e1, e2 = corner_uv[:, 1] - corner_uv[:, 0], corner_uv[:, 2] - corner_uv[:, 0]
    return 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])


def check_atlas(V, F, corner_uv, chart, report):
    """What every atlas of a mesh without degenerate faces must satisfy; returns the number of charts."""
    charts = len(report["charts"])
    assert corner_uv.shape == (len(F), 3, 2) and chart.shape == (len(F),)
    assert corner_uv.min() >= 0 and corner_uv.max() <= 1
    # Chart ids are exactly 0..charts-1, each chart's face count the report's.
    np.testing.assert_array_equal(np.bincount(chart, minlength=charts), [c["faces"] for c in report["charts"]])
    assert chart.min() == 0 and chart.max() == charts - 1
    # Corners of one vertex in one chart share their UV exactly (a chart is one continuous map): group the
    # corners by (chart, vertex) and compare each to the first of its group.
    key = np.repeat(chart, 3) * len(V) + F.ravel()
    order = np.argsort(key, kind="stable")
    sorted_key, sorted_uv = key[order], corner_uv.reshape(-1, 2)[order]
    first = np.searchsorted(sorted_key, sorted_key)
    np.testing.assert_array_equal(sorted_uv, sorted_uv[first])
    # Within its chart every triangle keeps its orientation: signed UV area > 0 (no flip), as reported.
    uv_area = signed_uv_areas(corner_uv)
    assert (uv_area > 0).all() and report["flipped"] == 0
    for c in report["charts"]:
        assert c["flipped"] == 0 and c["distortion"] == pytest.approx(c["energy"] / c["area"], rel=1e-12)
    # The bounds: overlap (rasterized) <= 1e-4, packing >= 0.5, area-weighted distortion <= 0.10.
    assert report["overlap_ratio"] <= 1e-4 and report["boundary_overlaps"] == 0
    assert report["packing_efficiency"] == pytest.approx(uv_area.sum(), rel=1e-12)
    assert report["packing_efficiency"] >= 0.5
    assert report["area"] == pytest.approx(triangle_areas(V, F).sum(), rel=1e-12)
    assert report["distortion"] == pytest.approx(report["energy"] / report["area"], rel=1e-12)
    assert report["distortion"] <= 0.10
    # One packing scale s for all charts. A chart's energy / area d = mean (s1 - 1)^2 + (s2 - 1)^2 over its
    # singular values bounds its UV area / surface area before packing: |mean s1 s2 - 1| <= sqrt(2 d) + d / 2
    # (Cauchy-Schwarz on s1 s2 - 1 = (s1 - 1)(s2 - 1) + (s1 - 1) + (s2 - 1)). So s^2 lies in every chart's
    # interval ratio / (1 +- delta): their intersection is not empty.
    ratio = np.bincount(chart, weights=uv_area) / np.bincount(chart, weights=triangle_areas(V, F))
    delta = np.array([np.sqrt(2 * c["distortion"]) + c["distortion"] / 2 for c in report["charts"]])
    assert (delta < 1).all()
    assert (ratio / (1 + delta)).max() <= (ratio / (1 - delta)).min() * (1 + 1e-9)
    for name in ("seam_length", "degenerate_faces", "merged_small_charts", "splits_for_distortion",
                 "splits_for_overlap", "segment_ms", "flatten_ms", "pack_ms", "parameterize_ms"):
        assert name in report
    assert report["seam_length"] > 0 and report["degenerate_faces"] == 0
    return charts


def seam_length(V, F, chart):
    """Length of the edges whose two faces lie in different charts (each counted once)."""
    half_edges = {}
    for f, face in enumerate(F):
        for k in range(3):
            a, b = face[k], face[(k + 1) % 3]
            half_edges[(a, b)] = chart[f]
    return sum(np.linalg.norm(V[a] - V[b]) for (a, b), c in half_edges.items()
               if a < b and half_edges[(b, a)] != c)


def test_closed_bunny(bunny):
    V, F = bunny
    corner_uv, chart, report = iarap.uv_atlas(V, F, texture_size=512)
    charts = check_atlas(V, F, corner_uv, chart, report)
    assert charts >= 2  # a closed surface is no disk
    assert report["seam_length"] == pytest.approx(seam_length(V, F, chart), rel=1e-12)


def test_torus():
    V, F = torus(48, 24)
    corner_uv, chart, report = iarap.uv_atlas(V, F, texture_size=512)
    charts = check_atlas(V, F, corner_uv, chart, report)
    assert charts >= 2  # genus 1: no disk, and no single chart
    assert report["seam_length"] == pytest.approx(seam_length(V, F, chart), rel=1e-12)


def test_two_pieces():
    V, F, torus_faces = two_pieces()
    corner_uv, chart, report = iarap.uv_atlas(V, F, texture_size=512)
    check_atlas(V, F, corner_uv, chart, report)
    # No chart joins the two pieces: the torus's charts and the sphere's are disjoint sets.
    assert not set(chart[:torus_faces]) & set(chart[torus_faces:])


def test_parameterize_names_uv_atlas_for_a_mesh_that_is_not_a_disk(bunny):
    V, F, _ = two_pieces()
    for mesh in (bunny, torus(12, 6), (V, F)):
        with pytest.raises(iarap.TopologyError, match=r"not a topological disk[\s\S]*iarap\.uv_atlas\(V, F\)"):
            iarap.parameterize(*mesh)
    # A non-manifold mesh cannot be cut into charts either: no hint there.
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], dtype=float)
    F = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(iarap.TopologyError) as refused:
        iarap.parameterize(V, F)
    assert "uv_atlas" not in str(refused.value)
