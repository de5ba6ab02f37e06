"""iarap.parameterize: the same map as `iarap param`, flip-free by default where the plain iteration folds,
and the errors of a mesh that is not a disk."""
import json
import subprocess

import numpy as np
import pytest

import iarap


def spherical_cap(rings, sectors, polar_angle):
    """The cap of the unit sphere within polar_angle of the north pole: a centre vertex and `rings` rings of
    `sectors` vertices (odd rings turned by half a sector), faces counter-clockwise seen from outside."""
    V = [[0.0, 0.0, 1.0]]
    for r in range(rings):
        theta = polar_angle * (r + 1) / rings
        for k in range(sectors):
            a = 2 * np.pi * (k + 0.5 * (r % 2)) / sectors
            V.append([np.sin(theta) * np.cos(a), np.sin(theta) * np.sin(a), np.cos(theta)])
    F = [[0, 1 + k, 1 + (k + 1) % sectors] for k in range(sectors)]
    for r in range(rings - 1):
        for k in range(sectors):
            a, b = 1 + r * sectors + k, 1 + r * sectors + (k + 1) % sectors
            c, d = a + sectors, b + sectors
            F += [[a, c, d], [a, d, b]]
    return np.array(V), np.array(F)


def det_J_signs(V, F, UV):
    """Sign of each triangle's UV area against its surface orientation (all faces are counter-clockwise
    seen from outside, so a kept orientation is a positive UV area)."""
    e1, e2 = UV[F[:, 1]] - UV[F[:, 0]], UV[F[:, 2]] - UV[F[:, 0]]
    return np.sign(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])


@pytest.fixture
def one_thread():
    before = iarap.thread_count()
    iarap.set_thread_count(1)
    yield
    iarap.set_thread_count(before)


def test_matches_cli(cli, tmp_path, one_thread):
    V, F = spherical_cap(6, 18, 0.6 * np.pi)
    iarap.write_mesh(tmp_path / "cap.off", V, F)
    run = subprocess.run([str(cli), "param", str(tmp_path / "cap.off"), "--out", str(tmp_path / "uv.txt"),
                          "--json", "--quiet", "--threads", "1"], capture_output=True, text=True, check=True)
    cli_report = json.loads(run.stdout)
    UV, report = iarap.parameterize(V, F)
    # One library, one input, one thread: the text file's 17 digits round-trip exactly.
    np.testing.assert_array_equal(UV, np.loadtxt(tmp_path / "uv.txt"))
    assert report["iterations"] == cli_report["iterations"]
    assert report["energy"] == cli_report["energy"]
    assert report["flipped"] == 0 and report["min_det_J"] > 0


def test_flip_free_where_the_plain_iteration_folds():
    # Most of the sphere: the plain iteration folds triangles at the rim (24 of 384, measured in C++).
    V, F = spherical_cap(8, 24, 0.9 * np.pi)
    UV_plain, plain = iarap.parameterize(V, F, allow_flips=True)
    assert plain["flipped"] > 0
    assert np.sum(det_J_signs(V, F, UV_plain) < 0) == plain["flipped"]
    UV, report = iarap.parameterize(V, F)
    assert report["flipped"] == 0
    assert np.all(det_J_signs(V, F, UV) > 0)
    assert UV.shape == (len(V), 2) and UV.dtype == np.float64
    assert len(report["energies"]) == report["iterations"] == len(report["gradient_norms"])
    assert report["accelerator"] == "newton" and report["converged"]
    assert report["stop_reason"] == "energy_tolerance"
    assert report["scaled_energy"] <= report["energy"] * (1 + 1e-12)
    assert report["area_distortion"]["min"] <= report["area_distortion"]["median"] <= report["area_distortion"]["max"]


def test_circle_boundary_defaults_to_harmonic():
    V, F = spherical_cap(5, 14, 0.4 * np.pi)
    UV, report = iarap.parameterize(V, F, boundary="circle")
    assert report["requested_init"] == "harmonic"
    assert report["pinned"] == 14
    radius = np.sqrt(report_area(V, F) / np.pi)
    np.testing.assert_allclose(np.linalg.norm(UV[-14:], axis=1), radius, rtol=1e-14)


def report_area(V, F):
    return 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()


def test_not_a_disk(sphere):
    V, F = sphere
    with pytest.raises(iarap.TopologyError, match="0 boundary loops and genus 0.*cut it into disks first"):
        iarap.parameterize(V, F)


def test_bad_arguments():
    V, F = spherical_cap(3, 8, 0.5 * np.pi)
    with pytest.raises(iarap.InputError, match="spectral"):
        iarap.parameterize(V, F, init="spectral")
    with pytest.raises(iarap.InputError, match="tutte or harmonic"):
        iarap.parameterize(V, F, boundary="circle", init="lscm")
    with pytest.raises(iarap.InputError, match=r"iterations must be an integer in \[0, 1000000\]; got -1"):
        iarap.parameterize(V, F, iterations=-1)
    V[3, 0] = np.nan
    with pytest.raises(iarap.InputError):
        iarap.parameterize(V, F)


@pytest.mark.parametrize("energy", ["arap", "iarap"])
def test_per_vertex_energies_are_flip_free(energy):
    V, F = spherical_cap(8, 24, 0.9 * np.pi)
    UV, report = iarap.parameterize(V, F, energy=energy, iterations=300)
    assert report["energy_kind"] == energy
    assert report["flipped"] == 0 and np.all(det_J_signs(V, F, UV) > 0)
    with pytest.raises(iarap.InputError, match="expected triangle, arap or iarap"):
        iarap.parameterize(V, F, energy="spokes-rims")


def test_pins_are_held_exactly():
    """Two pins: the map holds them to the bit and stays flip-free. Pinned where a rigid motion of the free
    minimizer puts them, that moved minimizer is feasible, so both runs converge to the same energy (run
    to a 1e-12 decrease so that the stopping rule, not the pins, sets the last digits: 1e-6 relative)."""
    V, F = spherical_cap(6, 18, 0.5 * np.pi)
    converge = dict(tolerance=1e-12, iterations=3000)
    free, free_report = iarap.parameterize(V, F, **converge)
    pins = np.array([3, 40])
    c, s = np.cos(0.3), np.sin(0.3)
    rotation = np.array([[c, -s], [s, c]])
    pin_uv = free[pins] @ rotation.T + np.array([2.0, -1.0])
    UV, report = iarap.parameterize(V, F, pins=pins, pin_uv=pin_uv, **converge)
    assert np.array_equal(UV[pins], pin_uv)
    assert report["pinned"] == 2 and report["flipped"] == 0
    assert report["energy"] == pytest.approx(free_report["energy"], rel=1e-6)


def test_bad_pins():
    V, F = spherical_cap(3, 8, 0.5 * np.pi)
    with pytest.raises(iarap.InputError, match="give both"):
        iarap.parameterize(V, F, pins=[0])
    with pytest.raises(iarap.InputError, match="pin_uv"):
        iarap.parameterize(V, F, pins=[0, 1], pin_uv=np.zeros((2, 3)))
    with pytest.raises(iarap.InputError, match="one UV position"):
        iarap.parameterize(V, F, pins=[0, 1], pin_uv=np.zeros((2, 2)))
    with pytest.raises(iarap.InputError):
        iarap.parameterize(V, F, pins=[0, 1000], pin_uv=np.eye(2))


def test_every_accelerator_of_the_engine():
    """The plain iteration's minimum (1e-4 relative: all stop at a 1e-9 decrease), flip-free; L-BFGS and Newton
    in fewer iterations (Anderson's mixed maps are often refused next to the injectivity bound: 71 against
    48 plain iterations here)."""
    V, F = spherical_cap(8, 24, 0.9 * np.pi)
    run = dict(tolerance=1e-9, iterations=3000)
    _, plain = iarap.parameterize(V, F, accelerator="none", **run)
    for accelerator in ("anderson", "lbfgs", "newton"):
        UV, report = iarap.parameterize(V, F, accelerator=accelerator, **run)
        assert report["accelerator"] == accelerator and report["converged"]
        if accelerator != "anderson":
            assert report["iterations"] < plain["iterations"]
        assert report["energy"] == pytest.approx(plain["energy"], rel=1e-4)
        assert report["flipped"] == 0 and np.all(det_J_signs(V, F, UV) > 0)
    _, budget = iarap.parameterize(V, F, accelerator="none", tolerance=-1, time_budget_ms=1e-3)
    assert budget["stop_reason"] == "time_budget" and budget["iterations"] == 1
    with pytest.raises(iarap.InputError, match="accelerator must be one of newton, hybrid, lbfgs, anderson, none; got adam"):
        iarap.parameterize(V, F, accelerator="adam")


def test_uv_atlas_of_a_closed_sphere(sphere):
    """A closed sphere (genus 0) becomes disk charts: per-corner UVs in the unit square, no flipped
    triangle, every face in a chart, and the report's figures as `iarap param` gives them."""
    V, F = sphere
    corner_uv, chart, report = iarap.uv_atlas(V, F, texture_size=256)
    assert corner_uv.shape == (len(F), 3, 2) and chart.shape == (len(F),)
    assert corner_uv.min() >= 0 and corner_uv.max() <= 1
    assert chart.min() == 0 and chart.max() == len(report["charts"]) - 1 >= 1  # a sphere is no disk
    e1, e2 = corner_uv[:, 1] - corner_uv[:, 0], corner_uv[:, 2] - corner_uv[:, 0]
    uv_area = 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    assert (uv_area > 0).all() and report["flipped"] == 0
    # packing_efficiency is the atlas's UV area (of the unit square): the same sum, to rounding.
    assert report["packing_efficiency"] == pytest.approx(uv_area.sum(), rel=1e-12)
    assert report["overlap_ratio"] <= 1e-4
    # The charts cover the surface once: their areas sum to the mesh's.
    assert report["area"] == pytest.approx(report_area(V, F), rel=1e-12)
    assert report["distortion"] == pytest.approx(report["energy"] / report["area"], rel=1e-12)
    assert report["distortion"] <= 0.10  # the bound
    # Corners of one vertex in one chart share their UV (a chart is one piece of the map).
    for c in range(len(report["charts"])):
        faces = np.flatnonzero(chart == c)
        seen = {}
        for f in faces:
            for k in range(3):
                seen.setdefault(F[f, k], corner_uv[f, k])
                assert np.array_equal(seen[F[f, k]], corner_uv[f, k])


def test_uv_atlas_refuses_bad_input():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], dtype=float)
    F = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])  # three triangles on one edge
    with pytest.raises(iarap.TopologyError, match="cannot be cut into disk charts"):
        iarap.uv_atlas(V, F)
    with pytest.raises(iarap.InputError, match="texture_size"):
        iarap.uv_atlas(V, F[:1], texture_size=4)
