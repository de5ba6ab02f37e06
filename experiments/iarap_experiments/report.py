"""Runs every section, renders the pictures, writes DIR/report.md, DIR/report.html and DIR/data/."""
from __future__ import annotations

import datetime
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import time
import traceback

from . import (section_convergence, section_fig8, section_gallery, section_lion, section_operator_identity,
               section_param_triangulation, section_rest_stability,
               section_symmetry, section_table1, section_table2, section_table3)
from .context import Context, Stopwatch
from .report_document import Document, Heading, Paragraph, Table, to_html, to_markdown

# One module per section, in report order; report.py numbers their headings (see number_headings).
SECTIONS = [("table1", section_table1), ("table2", section_table2), ("table3", section_table3),
            ("operator_identity", section_operator_identity), ("fig8", section_fig8), ("rest_stability", section_rest_stability), ("symmetry", section_symmetry),
            ("lion", section_lion), ("gallery", section_gallery), ("convergence", section_convergence),
            ("param_triangulation", section_param_triangulation)]
RENDERER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "render_vtk.py")


def render_pictures(ctx: Context) -> str | None:
    """Renders every queued job with VTK in one process; returns an error message or None."""
    if not ctx.render_jobs:
        return None
    job_files = []
    for k, job in enumerate(ctx.render_jobs):
        path = ctx.work(f"render_job_{k:02d}.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(job, f)
        job_files.append(path)
    command = [sys.executable, RENDERER, *job_files]
    if not os.environ.get("DISPLAY"):
        if shutil.which("xvfb-run") is None:
            return "no X display and no xvfb-run (install xvfb and python3-vtk9: scripts/install_deps.sh)"
        command = ["xvfb-run", "-a", "-s", "-screen 0 1920x1200x24"] + command
    done = subprocess.run(command, capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        return f"renderer failed ({done.returncode}): {done.stderr.strip()[-800:]}"
    missing = [job["out"] for job in ctx.render_jobs if not os.path.exists(job["out"])]
    return f"renderer wrote no {', '.join(missing)}" if missing else None


def number_headings(blocks: list, number: int) -> None:
    """Numbers a section's level-2 headings by its position in SECTIONS ("N. title"), replacing any number the
    section wrote itself, so adding or moving a section never leaves two sections with the same number."""
    for block in blocks:
        if isinstance(block, Heading) and block.level == 2:
            block.text = f"{number}. " + re.sub(r"^\d+\.\s*", "", block.text)


def closing_note(ctx: Context, doc: Document) -> None:
    doc.add(Heading("Closing note: every claim, our figure and the paper's"),
            Table(["section", "claim", "ours", "paper", "holds"],
                  [[c.section, c.claim, c.ours, c.paper, c.holds] for c in ctx.claims]))
    counts = {h: sum(c.holds.startswith(h) for c in ctx.claims) for h in ("yes", "partly", "no", "n/a")}
    doc.add(Paragraph(f"{counts['yes']} claims hold, {counts['partly']} partly, {counts['no']} do not, "
                      f"{counts['n/a']} are measurements without a paper claim to compare. Claims that do not hold "
                      "are reported as measured; nothing was tuned to make them hold."))


def cpu_seconds() -> float:
    """User + system CPU time of this process and its finished children (the CLI runs, the renderer)."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def build_report(ctx: Context) -> int:
    """Writes the report; returns the number of sections that failed (their error is in the report)."""
    started, cpu_started = time.perf_counter(), cpu_seconds()
    doc = Document()
    doc.add(Heading("Reproducing 'ARAP Revisited' (iARAP): experiments report", 1),
            Paragraph(f"Generated {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC} by "
                      f"`experiments/run_experiments.py`{' --quick (reduced report)' if ctx.quick else ''} with "
                      f"`{os.path.relpath(ctx.cli.path, ctx.repo)}` on {platform.node() or 'this machine'} "
                      f"({os.cpu_count()} hardware threads; all-core runs use {ctx.threads_all}). Meshes: "
                      f"{ctx.shared_meshes or 'bundled and generated only'}. Load average when it started: "
                      f"{os.getloadavg()[0]:.1f} (timings are disturbed when it exceeds the core count). "
                      "Raw data: `data/` (JSON and CSV). "
                      "Each section states the paper's claim, our measurement and whether it holds."))
    failures = 0
    for number, (name, module) in enumerate(SECTIONS, start=1):
        first = len(doc.blocks)
        try:
            with Stopwatch(ctx, name):
                module.run(ctx, doc)
        except Exception as error:  # a failed section is reported, the others still run
            failures += 1
            doc.add(Heading(f"{name}: FAILED"), Paragraph(f"`{type(error).__name__}`: {error}"))
            ctx.claim(name, "section ran", f"failed: {type(error).__name__}", "-", "no")
            traceback.print_exc()
        number_headings(doc.blocks[first:], number)
        print(f"experiments: {name} done ({ctx.timings.get(name, 0):.1f} s)", file=sys.stderr, flush=True)
    with Stopwatch(ctx, "render"):
        render_error = render_pictures(ctx)
    if render_error:
        failures += 1
        doc.add(Paragraph(f"**Pictures missing:** {render_error}"))
        ctx.claim("pictures", "all pictures rendered", render_error, "-", "no")
    closing_note(ctx, doc)
    total, cpu = time.perf_counter() - started, cpu_seconds() - cpu_started
    doc.add(Paragraph("Run time per section (wall-clock s): " + ", ".join(f"{k} {v:.1f}" for k, v in ctx.timings.items()) +
                      f"; total {total:.1f} s wall-clock, {cpu:.1f} s of CPU time (all processes; on a machine "
                      "shared with other jobs the wall-clock time grows, the CPU time does not)."))
    with open(ctx.path("report.md"), "w", encoding="utf-8") as f:
        f.write(to_markdown(doc))
    with open(ctx.path("report.html"), "w", encoding="utf-8") as f:
        f.write(to_html(doc, ctx.out, "iARAP experiments report"))
    ctx.write_json("claims.json", [c.__dict__ for c in ctx.claims])
    ctx.write_json("timings.json", {**ctx.timings, "total": total, "cpu_seconds": cpu})
    return failures
