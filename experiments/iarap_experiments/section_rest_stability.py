"""Rest stability (Sec. 5, Fig. 9): constraints left at rest, how far does each method drift?"""
from __future__ import annotations

import json
import re

from .cli import CliError
from .context import METHOD_LABELS, METHODS, Context, fmt
from .report_document import Heading, Paragraph, Table

SCENARIO = {"description": "rest stability: bottom 10% along y fixed at rest, nothing moved",
            "fixed": {"bottom": 0.1, "axis": "y"}}
# Starting at rest, rotations are the identity up to round-off and the global step reproduces V up to the
# solver's round-off (~1e-13 relative); 1e-8 of the bbox diagonal separates that from real drift.
STAYS = 1e-8
SHARED = ["planexy.off", "grid.off", "cube.obj", "decimated-knight.off", "spike.ply", "halftunnel.off",
          "bunny.off", "3holes.off", "fertility.off", "horse.obj", "cactus.obj", "elephant.obj",
          "cheburashka.off", "lion.off", "camelhead.off", "armadillo_30K.obj", "beetle.off", "bumpy-cube.obj",
          "face.obj", "armadillo.obj", "ogre.obj", "igea.ply"]  # cube_40k.obj is not a surface


def boundary_variant(ctx: Context) -> tuple[str, list[str]] | None:
    """(method, extra CLI arguments) of the boundary-robust iARAP (issue 8) when the CLI offers it."""
    text = ctx.cli.help_text("deform")
    if re.search(r"--boundary\b", text):
        return "iarap", ["--boundary", "refine"]
    choices = re.search(r"--method\s+\S*\s*([^\n]*)", text)
    for name in re.findall(r"[a-z][a-z-]*refine[a-z-]*|[a-z][a-z-]*boundary[a-z-]*", choices.group(1) if choices else ""):
        return name, []
    return None


def variants(ctx: Context) -> list[tuple[str, str, list[str]]]:
    found = [(m, m, []) for m in METHODS]
    extra = boundary_variant(ctx)
    if extra:
        found.append(("iarap-refine", extra[0], extra[1]))
    return found


def meshes(ctx: Context) -> list[tuple[str, str]]:
    return ctx.meshes_present(SHARED)


def run(ctx: Context, doc) -> None:
    checkpoints = [10, 50] if ctx.quick else [10, 50, 200]
    scenario = ctx.work("rest_scenario.json")
    with open(scenario, "w", encoding="utf-8") as f:
        json.dump(SCENARIO, f)
    results, skipped, refused = [], [], []
    for label, path in meshes(ctx):
        info = ctx.cli.info(path)
        if not info.get("usable", False):
            skipped.append(f"`{label}` ({'; '.join(info.get('errors', []))[:160]})")
            continue
        intrinsic = ctx.cli.intrinsic(path)
        row = {"mesh": label, "vertices": info["vertices"], "non_delaunay_edges": info["non_delaunay_edges"],
               "boundary_edges": info["boundary_edges"],
               "obtuse_boundary_edges": intrinsic.get("obtuse_boundary_before", "-"),
               "bbox_diagonal": info["bbox_diagonal"], "drift": {}, "iterations": {}}
        for name, method, extra in variants(ctx):
            row["drift"][name], row["iterations"][name] = {}, {}
            for iterations in checkpoints:
                try:
                    r = ctx.cli.deform(path, ctx.work("rest_out.off"), method, iterations, scenario=scenario,
                                       tolerance=0.0, extra=extra)
                except CliError as error:  # e.g. original ARAP refuses zero-area faces (ogre.obj)
                    refused.append(f"{METHOD_LABELS.get(name, name)} on `{label}`: {str(error).splitlines()[-1][:160]}")
                    row["drift"][name][str(iterations)] = float("nan")
                    row["iterations"][name][str(iterations)] = 0
                    break
                row["drift"][name][str(iterations)] = r["max_displacement"] / r["bbox_diagonal"]
                row["iterations"][name][str(iterations)] = r["iterations"]
            for iterations in checkpoints:  # a refused method fills every checkpoint
                row["drift"][name].setdefault(str(iterations), float("nan"))
                row["iterations"][name].setdefault(str(iterations), 0)
        results.append(row)
    ctx.write_json("rest_stability.json", results)
    names = [n for n, _, _ in variants(ctx)]
    ctx.write_csv("rest_stability.csv", ["mesh", "vertices", "non_delaunay_edges", "boundary_edges",
                                         "obtuse_boundary_edges"] +
                  [f"{n}_{k}" for n in names for k in checkpoints],
                  [[r["mesh"], r["vertices"], r["non_delaunay_edges"], r["boundary_edges"], r["obtuse_boundary_edges"]]
                   + [r["drift"][n][str(k)] for n in names for k in checkpoints] for r in results])
    doc.add(Heading("Rest stability (Sec. 5, Fig. 9)"),
            Paragraph("**Paper:** original ARAP's negative cotan weights make its energy negative on non-Delaunay "
                      "meshes, so it creases 'already without displacing the constraints'; spokes-and-rims and "
                      "iARAP are non-negative and stay at rest. iARAP never flips boundary edges, so a boundary "
                      "edge whose opposite angle is obtuse keeps a negative weight.\n\n"
                      f"**Measured:** bottom 10% along y fixed at rest, nothing moved, `iarap deform --tolerance 0` "
                      f"for {', '.join(map(str, checkpoints))} iterations; max vertex drift / bbox diagonal "
                      f"('0' = exactly at rest; 'stays' = below {STAYS:g}). Non-Delaunay: interior edges with "
                      "negative cotan weight (`iarap info`); obtuse boundary: boundary edges whose opposite angle "
                      "is obtuse (`iarap intrinsic`). A run stops before its iteration count only when its energy stops "
                      "decreasing (the CLI's rule with tolerance 0), e.g. when it is exactly 0 at rest (a global "
                      "minimum of a non-negative energy); the iterations actually run are in "
                      "`data/rest_stability.json`."
                      + ("" if len(names) > 3 else " The boundary-robust variant (issue 8) is not in this CLI "
                         "yet (`iarap deform --help` offers no boundary option), so it is not measured.")))
    header = ["mesh", "V", "non-Delaunay", "boundary", "obtuse boundary"] + \
        [f"{METHOD_LABELS[n]} @{k}" for n in names for k in checkpoints]
    if skipped:
        doc.add(Paragraph("Not usable for ARAP as they are (`iarap info` errors), so not measured: " +
                          ", ".join(skipped) + "."))
    if refused:
        doc.add(Paragraph("Refused by the method (nan in the table): " + "; ".join(refused) + "."))
    doc.add(Table(header, [[r["mesh"], str(r["vertices"]), str(r["non_delaunay_edges"]), str(r["boundary_edges"]),
                            str(r["obtuse_boundary_edges"])] + [fmt(r["drift"][n][str(k)], 2) for n in names
                                                               for k in checkpoints] for r in results]))
    last = str(checkpoints[-1])
    closed = [r for r in results if r["boundary_edges"] == 0]
    closed_nd = [r for r in closed if r["non_delaunay_edges"] > 0]
    arap_drifts = sum(r["drift"]["arap"][last] > STAYS for r in closed_nd)
    others_stay = all(r["drift"][m][last] <= STAYS for r in closed for m in ("spokes-rims", "iarap"))
    bounded = [r for r in results if r["boundary_edges"] > 0]
    iarap_boundary_drift = [r["mesh"] for r in bounded if r["drift"]["iarap"][last] > STAYS]
    obtuse_meshes = [r["mesh"] for r in bounded if r["obtuse_boundary_edges"] not in ("-", 0)]
    ctx.claim("Rest stability", "closed non-Delaunay meshes: original ARAP drifts from rest",
              f"drifts on {arap_drifts} of {len(closed_nd)} closed non-Delaunay meshes", "creases without "
              "displacing the constraints (Fig. 9)",
              "yes" if closed_nd and arap_drifts == len(closed_nd) else ("partly" if arap_drifts else "no"))
    ctx.claim("Rest stability", "closed meshes: spokes-and-rims and iARAP stay at rest",
              f"{'all stay' if others_stay else 'some drift'} (max {fmt(max([r['drift'][m][last] for r in closed for m in ('spokes-rims', 'iarap')] or [0]), 2)})",
              "non-negative energies, no artefacts", "yes" if others_stay else "no")
    if bounded:
        ctx.claim("Rest stability", "meshes with boundary: iARAP keeps negative weights on obtuse boundary "
                  "edges and may drift", f"iARAP drifts on {len(iarap_boundary_drift)} of {len(bounded)} meshes with "
                  f"boundary ({', '.join(iarap_boundary_drift) or 'none'}); obtuse boundary edges on "
                  f"{', '.join(obtuse_meshes) or 'none'}", "not discussed (boundary edges are never flipped)", "n/a")
    if "iarap-refine" in names and bounded:
        refined_stays = all(r["drift"]["iarap-refine"][last] <= STAYS for r in results)
        ctx.claim("Rest stability", "boundary-robust iARAP stays at rest everywhere (not in the paper)",
                  "all stay" if refined_stays else "some drift", "-", "yes" if refined_stays else "no")
    calm = [r["mesh"] for r in closed_nd if r["drift"]["arap"][last] <= STAYS]
    doc.add(Paragraph(f"**Holds?** Original ARAP drifts on {arap_drifts} of the {len(closed_nd)} closed non-Delaunay "
                      f"meshes{' (it stays on ' + ', '.join(calm) + ': presumably their few or weak negative weights leave the energy non-negative)' if calm else ''}; spokes-and-rims and iARAP {'stay at rest on every closed mesh' if others_stay else 'drift on some closed mesh'}. "
                      f"With boundary, iARAP drifts on: {', '.join(iarap_boundary_drift) or 'none'}."))
