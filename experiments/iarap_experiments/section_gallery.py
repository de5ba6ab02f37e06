"""Fig. 9 and the gallery: rest mesh and the three results side by side (bunny ears, cube, lion)."""
from __future__ import annotations

import json
import os

import numpy as np

from .context import METHOD_LABELS, METHODS, Context, fmt
from .mesh_io import bbox_diagonal, read_mesh
from .report_document import Heading, Image, Paragraph


def scenario_vertices(V: np.ndarray, region: dict) -> np.ndarray:
    """Vertices of a {"bottom"|"top": fraction, "axis": a} scenario region (bounding-box rule of the CLI)."""
    axis = "xyz".index(region["axis"])
    lo, hi = V[:, axis].min(), V[:, axis].max()
    if "bottom" in region:
        return np.where(V[:, axis] <= lo + region["bottom"] * (hi - lo))[0]
    return np.where(V[:, axis] >= hi - region["top"] * (hi - lo))[0]


def run(ctx: Context, doc) -> None:
    bunny = ctx.bundled("bunny.off")
    scenario = ctx.bundled("bunny_scenario.json")
    with open(scenario, encoding="utf-8") as f:
        scene = json.load(f)
    V = read_mesh(bunny).V
    constrained = np.concatenate([scenario_vertices(V, scene["fixed"])] +
                                 [scenario_vertices(V, h["vertices"]) for h in scene["handles"]])
    iterations = 20 if ctx.quick else 100
    outputs, energies = {}, {}
    for method in METHODS:
        out = ctx.work(f"gallery_bunny_{method}.obj")
        r = ctx.cli.deform(bunny, out, method, iterations, scenario=scenario, tolerance=1e-8)
        outputs[method], energies[method] = out, r["energies"][-1] if r["energies"] else r["initial_energy"]
    rest_obj = ctx.work("gallery_bunny_rest.obj")
    from .mesh_io import write_obj
    write_obj(rest_obj, V, read_mesh(bunny).F)
    rest_to_iarap = {m: float(np.linalg.norm(read_mesh(outputs[m]).V - read_mesh(outputs["iarap"]).V, axis=1).max())
                     / bbox_diagonal(V) for m in METHODS}
    for name, view in (("front", {"direction": [0.0, 0.1, 1.0], "up": [0, 1, 0]}),
                       ("ears", {"direction": [0.0, 0.1, 1.0], "up": [0, 1, 0], "zoom": 1.2})):
        job = {"out": ctx.path(f"fig9_bunny_{name}.png"), "panel_size": [300, 330], "view": view,
               "panels": [{"title": "rest", "layers": [{"obj": rest_obj, "highlight": constrained.tolist()}]}] +
                         [{"title": METHOD_LABELS[m], "layers": [{"obj": outputs[m], "highlight": constrained.tolist()}]}
                          for m in METHODS]}
        if name == "ears":
            ears = scenario_vertices(V, scene["handles"][0]["vertices"])
            job["frame_points"] = np.vstack([read_mesh(outputs[m]).V[ears] for m in METHODS] +
                                            [V[ears]]).tolist()
        ctx.render_jobs.append(job)
    ctx.write_json("gallery_bunny.json", {"energies": energies, "distance_to_iarap": rest_to_iarap})
    doc.add(Heading("Fig. 9 and the gallery"),
            Paragraph("**Paper (Fig. 9):** the bunny's ill-shaped ear triangles make original ARAP crease; "
                      "spokes-and-rims and iARAP give similar, better results (Fig. 10: often very similar).\n\n"
                      f"**Bunny:** `data/bunny_scenario.json` ({scene['description']}), up to {iterations} "
                      "iterations (tolerance 1e-8), rendered with VTK. Max vertex distance to the iARAP result / "
                      "bbox diagonal: " + ", ".join(f"{METHOD_LABELS[m]} {fmt(rest_to_iarap[m])}" for m in METHODS
                                                     if m != "iarap") + "."),
            Image("fig9_bunny_front.png", "Bunny: rest (constrained vertices red), original ARAP, spokes-and-rims, "
                                          "iARAP."),
            Image("fig9_bunny_ears.png", "Bunny, close-up of the ears (same runs)."))
    for picture, caption in (("symmetry_Fig11.png", "Cube (Fig. 11), from the symmetry section."),
                             ("fig14_lion_results.png", "Lion (Fig. 14), from the Fig. 14 section.")):
        if ctx.quick and picture.startswith("fig14"):
            continue
        doc.add(Image(picture, caption))
    closer = rest_to_iarap["spokes-rims"] < rest_to_iarap["arap"]
    ctx.claim("Fig. 9", "bunny: spokes-and-rims and iARAP similar, original ARAP differs (creases at the ears)",
              f"distance to iARAP: spokes-and-rims {fmt(rest_to_iarap['spokes-rims'])}, original "
              f"{fmt(rest_to_iarap['arap'])} (x bbox diagonal); see the pictures",
              "visual (Fig. 9)", "yes" if closer else "no")
    if not os.path.exists(ctx.path("symmetry_Fig11.png")) and not ctx.render_jobs:
        doc.add(Paragraph("Pictures missing: the renderer did not run."))
