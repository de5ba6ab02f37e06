"""Table 2: iARAP local-step time at a fixed vertex and edge count and a growing segments/edges ratio."""
from __future__ import annotations

import numpy as np

from .context import Context, fmt, load_note
from .generated_meshes import flipped_lattice
from .mesh_io import write_obj
from .report_document import Heading, Paragraph, Table

PAPER = [(1.05, 62.9), (1.16, 65.8), (1.29, 69.5)]  # (segments per edge, local step ms), 35K V, 105K E
FRACTIONS = [0.0, 0.15, 0.5, 0.9]  # share of one lattice direction's edges flipped


def run(ctx: Context, doc) -> None:
    side = 30 if ctx.quick else 187  # 187^2 = 34969 vertices, ~104K edges like the paper's 35K / 105K
    iterations = 3 if ctx.quick else 20
    repeats = 1 if ctx.quick else 3
    rows_data = []
    for fraction in FRACTIONS:
        V, F, flips = flipped_lattice(side, side, fraction, seed=7)
        path = ctx.work(f"lattice_{side}_{int(fraction * 100):03d}.obj")
        write_obj(path, V, F)
        intrinsic = ctx.cli.intrinsic(path, threads=1)
        rows_data.append({"fraction_flipped": fraction, "flips": flips, "vertices": int(len(V)),
                          "intrinsic_edges": intrinsic["intrinsic_edges"], "segments": intrinsic["segments"],
                          "segments_per_edge": intrinsic["segments_per_edge"],
                          "non_delaunay_before": intrinsic["non_delaunay_before"], "path": path,
                          "local_ms": float("inf"), "global_ms": float("inf"), "iteration_ms": float("inf")})
    # Rows are timed in turn, `repeats` rounds, keeping each row's fastest median: load from other
    # processes only ever adds time, and interleaving spreads it over the rows instead of one row.
    for _ in range(repeats):
        for row in rows_data:
            r = ctx.cli.bench([row["path"]], threads=1, iterations=iterations, methods=["iarap"])["results"][0]
            for key in ("local_ms", "global_ms", "iteration_ms"):
                row[key] = min(row[key], r[key])
    for row in rows_data:
        del row["path"]
    ctx.write_json("table2.json", rows_data)
    ctx.write_csv("table2.csv", list(rows_data[0].keys()), [list(r.values()) for r in rows_data])
    doc.add(Heading("Table 2: local step vs. segments per intrinsic edge"),
            Paragraph("**Paper:** at 35K vertices and 105K edges, the local step takes 62.9 / 65.8 / 69.5 ms at "
                      "1.05 / 1.16 / 1.29 segments per intrinsic edge: the overhead grows with the number of "
                      "crossings, mildly.\n\n"
                      f"**Our family** (generated, `generated_meshes.flipped_lattice`): a flat {side} x {side} "
                      "equilateral triangular lattice (all edges Delaunay) in which a random share of the "
                      "edges of ONE lattice direction is flipped. Every triangle has exactly one edge of each "
                      "direction, so the flipped edges never share a triangle; each flip makes one non-Delaunay "
                      "edge (opposite angles 120 + 120 degrees) whose intrinsic replacement is traced as 2 "
                      "segments. Vertex and edge counts stay fixed and the ratio is 1 + flips / edges, up to "
                      f"4/3. Local step = median over {iterations} iterations of `iarap bench --methods iarap "
                      f"--threads 1` (its fixed scene), the fastest of {repeats} interleaved rounds."))
    rows = [[f"{r['fraction_flipped']:.2f}", str(r["vertices"]), str(r["intrinsic_edges"]), str(r["segments"]),
             f"{r['segments_per_edge']:.3f}", fmt(r["local_ms"]), fmt(r["global_ms"])] for r in rows_data]
    doc.add(Table(["flipped share", "vertices", "intrinsic edges", "segments", "segments / edges",
                   "local step (ms)", "global step (ms)"], rows),
            Table(["paper: segments / edges"] + [f"{s}" for s, _ in PAPER],
                  [["paper: local step (ms)"] + [f"{t}" for _, t in PAPER]]))
    first, last = rows_data[0], rows_data[-1]
    # The paper's baseline is 1.05 segments per edge, not 1.0: measure the growth from our row nearest 1.05
    # as well, so both ends of the comparison match the paper's.
    base = min(rows_data, key=lambda r: abs(r["segments_per_edge"] - PAPER[0][0]))
    growth = last["local_ms"] / base["local_ms"] - 1.0
    ratio_growth = last["segments_per_edge"] / base["segments_per_edge"] - 1.0
    growth_from_one = last["local_ms"] / first["local_ms"] - 1.0
    ratio_growth_from_one = last["segments_per_edge"] / first["segments_per_edge"] - 1.0
    paper_growth = PAPER[-1][1] / PAPER[0][1] - 1.0
    paper_ratio_growth = PAPER[-1][0] / PAPER[0][0] - 1.0
    # Cost per extra segment against the cost per edge at 1.0: slope of a least-squares line through the rows.
    segments = np.array([r["segments"] for r in rows_data], dtype=float)
    local = np.array([r["local_ms"] for r in rows_data])
    slope, intercept = np.polyfit(segments, local, 1)
    per_segment_share = slope * first["segments"] / first["local_ms"]
    # The paper's time grows less than the segment count (fixed per-vertex work dominates): holds when
    # ours grows too, and by no more than the segment count itself.
    # Growth below 2% is within the run-to-run noise of these timings: not a measured growth.
    holds = 0.02 < growth <= ratio_growth * 1.5
    verdict = ("yes" if holds else ("no (no growth beyond noise)" if growth <= 0.02 else "no")) + load_note(ctx)
    ctx.claim("Table 2", "local-step time grows mildly with segments per intrinsic edge",
              f"{growth * 100:+.1f}% for segments/edge {base['segments_per_edge']:.3f} -> "
              f"{last['segments_per_edge']:.3f} (+{ratio_growth * 100:.1f}%); {growth_from_one * 100:+.1f}% from "
              f"{first['segments_per_edge']:.3f}",
              f"+{paper_growth * 100:.1f}% for 1.05 -> 1.29 (+{paper_ratio_growth * 100:.1f}%)", verdict)
    doc.add(Paragraph(f"**Holds?** {verdict}: from the paper's baseline, local step {fmt(base['local_ms'])} -> "
                      f"{fmt(last['local_ms'])} ms ({growth * 100:+.1f}%) while segments per edge grow from "
                      f"{base['segments_per_edge']:.3f} to {last['segments_per_edge']:.3f} "
                      f"(+{ratio_growth * 100:.1f}%); the paper reports +{paper_growth * 100:.1f}% for "
                      f"+{paper_ratio_growth * 100:.1f}%. From 1.000 (no crossing): {growth_from_one * 100:+.1f}% for "
                      f"+{ratio_growth_from_one * 100:.1f}%. "
                      + (f"A least-squares line through the rows gives {slope * 1e3:.3g} ms per 1000 segments; at 1.000 "
                         f"segments per edge the segment-proportional part is {per_segment_share * 100:.0f}% of the "
                         "local step, the rest is per-vertex work (one polar decomposition per cell), which is why the "
                         "time grows less than the segment count. " if slope > 0 else
                         "No positive cost per segment is measurable in this run: the timings are dominated by other "
                         "load on the machine, not by the segments. ")
                      + "Rule: "
                      "the time must grow by more than 2% (noise) and at most 1.5x the growth of the segment "
                      "count (from the 1.05 row)."))
