"""Table 1: precomputation and per-iteration times of the three methods on ~3K, ~20K and ~200K meshes."""
from __future__ import annotations

import numpy as np

from .context import METHOD_LABELS, METHODS, Context, fmt, load_note
from .mesh_io import read_mesh
from .report_document import Heading, Paragraph, Table

# Paper Table 1 (ms, single thread, AMD Ryzen 7 2700X): (precompute, step) per model and method.
PAPER = {
    "3K": {"arap": (55, 3.2), "spokes-rims": (46, 3.2), "iarap": (80, 5.2)},
    "20K": {"arap": (336, 23.5), "spokes-rims": (280, 22.7), "iarap": (507, 37.1)},
    "200K": {"arap": (943, 72.7), "spokes-rims": (825, 75.9), "iarap": (1405, 95.5)},
}
# Verdict thresholds: the paper's iARAP/original ratios are 1.45-1.51 (precompute) and 1.31-1.63 (step).
# "Comparable" is read as: iARAP costs at most 2x original ARAP per iteration and 3x in precomputation.
MAX_STEP_RATIO, MAX_PRE_RATIO = 2.0, 3.0


def models(ctx: Context) -> list[tuple[str, str, str, int]]:
    """(class, label, path, subdivisions) of the meshes present."""
    found = [("3K", "bunny.off", ctx.bundled("bunny.off"), 0)]
    if ctx.quick:
        return found
    beetle, armadillo = ctx.shared("beetle.off"), ctx.shared("armadillo.obj")
    if beetle:
        found.append(("20K", "beetle.off", beetle, 0))
    if armadillo:
        found.append(("200K", "armadillo.obj, 1-to-4 subdivided", armadillo, 1))
    return found


def run(ctx: Context, doc) -> None:
    iterations = 3 if ctx.quick else 5
    thread_settings = [1] if ctx.quick else sorted({1, ctx.threads_all})
    repeats = 1 if ctx.quick else 2
    note = load_note(ctx)
    best = {}
    # Each configuration is timed `repeats` times in turn, keeping the fastest figure of each kind: load
    # from other processes only ever adds time.
    for _ in range(repeats):
        for klass, label, path, subdivide in models(ctx):
            for threads in thread_settings:
                bench = ctx.cli.bench([path], threads=threads, iterations=iterations, subdivide=subdivide)
                for r in bench["results"]:
                    r.update({"class": klass, "label": label, "threads": threads, "cpu": bench["cpu"]})
                    key = (klass, r["method"], threads)
                    if key not in best:
                        best[key] = r
                    else:
                        for field in ("precompute_ms", "intrinsic_ms", "iteration_ms", "local_ms", "global_ms"):
                            best[key][field] = min(best[key][field], r[field])
    results = list(best.values())
    ctx.write_json("table1.json", results)
    ctx.write_csv("table1.csv", ["class", "mesh", "vertices", "method", "threads", "precompute_ms",
                                 "intrinsic_ms", "iteration_ms", "local_ms", "global_ms"],
                  [[r["class"], r["label"], r["vertices"], r["method"], r["threads"], r["precompute_ms"],
                    r["intrinsic_ms"], r["iteration_ms"], r["local_ms"], r["global_ms"]] for r in results])

    doc.add(Heading("Table 1: precomputation and iteration times"),
            Paragraph("**Paper:** iARAP's precomputation adds the intrinsic Delaunay triangulation (about 1.5x "
                      "original ARAP) and each iteration is comparable to the other two variants (1.3x-1.6x), "
                      "single-threaded on a Ryzen 7 2700X.\n\n"
                      f"**Measured:** `iarap bench` (its fixed scene: bottom 10% along y fixed, top 10% moved "
                      f"by 10% of the bounding-box diagonal), median of {iterations} iterations after one "
                      f"warm-up, fastest of {repeats} interleaved rounds, on `{results[0]['cpu'] if results else '?'}`; threads = 1 and all "
                      f"({ctx.threads_all}) cores. The ~200K mesh is `armadillo.obj` subdivided 1-to-4 by "
                      "`iarap bench --subdivide 1` (the library's midpoint subdivision). Times in ms."))
    rows = []
    verdicts = []
    by_key = {(r["class"], r["method"], r["threads"]): r for r in results}
    for klass, label, _, _ in models(ctx):
        for threads in thread_settings:
            base = by_key.get((klass, "arap", threads))
            for method in METHODS:
                r = by_key.get((klass, method, threads))
                if r is None:
                    continue
                paper_pre, paper_step = PAPER[klass][method]
                pre_ratio = r["precompute_ms"] / base["precompute_ms"]
                step_ratio = r["iteration_ms"] / base["iteration_ms"]
                paper_pre_ratio = paper_pre / PAPER[klass]["arap"][0]
                paper_step_ratio = paper_step / PAPER[klass]["arap"][1]
                rows.append([f"{label} ({r['vertices']} V)", METHOD_LABELS[method], str(threads),
                             fmt(r["precompute_ms"]), fmt(r["intrinsic_ms"]), fmt(r["iteration_ms"]),
                             fmt(r["local_ms"]), fmt(r["global_ms"]), f"{pre_ratio:.2f} / {step_ratio:.2f}",
                             f"{paper_pre} / {paper_step}", f"{paper_pre_ratio:.2f} / {paper_step_ratio:.2f}"])
                if method == "iarap" and threads == 1:
                    verdicts.append((klass, pre_ratio, step_ratio, paper_pre_ratio, paper_step_ratio))
    doc.add(Table(["mesh", "method", "threads", "pre", "of which intrinsic", "step", "local", "global",
                   "ratio to original (pre / step)", "paper (pre / step)", "paper ratio"], rows))
    for klass, pre_ratio, step_ratio, paper_pre_ratio, paper_step_ratio in verdicts:
        holds = step_ratio <= MAX_STEP_RATIO and pre_ratio <= MAX_PRE_RATIO
        ctx.claim("Table 1", f"{klass}: iARAP precompute and step comparable to original ARAP "
                  f"(step <= {MAX_STEP_RATIO}x, precompute <= {MAX_PRE_RATIO}x)",
                  f"pre {pre_ratio:.2f}x, step {step_ratio:.2f}x (1 thread)",
                  f"pre {paper_pre_ratio:.2f}x, step {paper_step_ratio:.2f}x", ("yes" if holds else "no") + note)
    doc.add(Paragraph("**Holds?** " + "; ".join(
        f"{k}: iARAP/original = {p:.2f}x precompute, {s:.2f}x per step (paper {pp:.2f}x, {ps:.2f}x) -> "
        f"{'yes' if s <= MAX_STEP_RATIO and p <= MAX_PRE_RATIO else 'no'}"
        for k, p, s, pp, ps in verdicts) + f". Verdict rule: step ratio <= {MAX_STEP_RATIO} and precompute "
        f"ratio <= {MAX_PRE_RATIO}. Absolute times depend on the machine and are not comparable 1:1.{note}"))
    explain(ctx, doc, by_key)


def element_counts(ctx: Context, path: str, subdivide: int) -> dict:
    """(element, rotation cell) pairs each method's local step and right-hand side visit: original ARAP one
    element per edge with 2 cells, spokes-and-rims one per (face, edge) with the face's 3 cells, iARAP one
    per segment with 2 cells. Counts after `subdivide` midpoint 1-to-4 subdivisions (E -> 2E + 3F, F -> 4F)."""
    mesh = read_mesh(path)
    F = mesh.F
    edges = len(np.unique(np.sort(np.vstack([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1), axis=0))
    faces, vertices = len(F), len(mesh.V)
    for _ in range(subdivide):
        vertices, edges, faces = vertices + edges, 2 * edges + 3 * faces, 4 * faces
    segments = ctx.cli.intrinsic(path, subdivide=subdivide)["segments"]
    return {"vertices": vertices, "edges": edges, "faces": faces, "segments": segments,
            "pairs": {"arap": 2 * edges, "spokes-rims": 9 * faces, "iarap": 2 * segments}}


def explain(ctx: Context, doc, by_key: dict) -> None:
    """Why iARAP's iteration costs what original ARAP's does, and why spokes-and-rims costs more."""
    rows, data = [], []
    for klass, label, path, subdivide in models(ctx):
        base = by_key.get((klass, "arap", 1))
        if base is None:
            continue
        counts = element_counts(ctx, path, subdivide)
        entry = {"class": klass, **counts}
        for method in ("spokes-rims", "iarap"):
            r = by_key.get((klass, method, 1))
            if r is None:
                continue
            entry[method] = {k: r[k] / base[k] for k in ("local_ms", "global_ms", "iteration_ms")}
            rows.append([f"{label}", METHOD_LABELS[method], f"{counts['pairs'][method] / counts['pairs']['arap']:.2f}",
                         f"{entry[method]['local_ms']:.2f}", f"{entry[method]['global_ms']:.2f}",
                         f"{entry[method]['iteration_ms']:.2f}"])
        data.append(entry)
    ctx.write_json("table1_element_counts.json", data)
    if not rows:
        return
    sr = [d["spokes-rims"]["iteration_ms"] for d in data if "spokes-rims" in d]
    ia = [d["iarap"]["iteration_ms"] for d in data if "iarap" in d]
    spe = [d["segments"] / d["edges"] for d in data]
    span = lambda v: f"{min(v):.2f}" if min(v) == max(v) else f"{min(v):.2f}-{max(v):.2f}"  # noqa: E731
    doc.add(Paragraph("**Why the step costs what it costs** (1 thread, ratios to original ARAP from the table above). "
                      "An iteration is a local step (one 3x3 polar decomposition per vertex cell plus a sum over "
                      "(element, cell) pairs for the covariances) and a global step (the right-hand side, another "
                      "sum over the same pairs, then two triangular solves with the factorization). Original ARAP "
                      "visits 2 pairs per edge (2E), spokes-and-rims 3 cells for each of its 3 elements per face "
                      "(9F, about 3 x 2E on a closed mesh), iARAP 2 per segment (2S)."),
            Table(["mesh", "method", "(element, cell) pairs / original's", "local step", "global step", "iteration"], rows),
            Paragraph(f"- **iARAP costs what original ARAP costs** ({span(ia)}x per iteration{load_note(ctx)}): its "
                      "global step solves with the same matrix, because the iARAP matrix B^T D_w B *is* the cotan "
                      "Laplacian (section \"The iARAP operator is the cotan Laplacian\"), so the factorization and "
                      "the solves are identical; only the sums run over segments instead of edges, "
                      f"{span(spe)} segments per edge on these meshes, so only the sums can cost more, by at most that "
                      "factor. (The paper measured 1.3-1.6x.)\n"
                      f"- **Spokes-and-rims costs {span(sr)}x**{load_note(ctx)} because it visits about 3x the "
                      "(element, cell) pairs of original ARAP in the local step and in the right-hand side, while the "
                      "polar decompositions (one per vertex) and the solve (same matrix size and pattern) are the "
                      "same: the pair sums are a part of the iteration, not all of it, so 3x the pairs gives well "
                      "under 3x the time."))
