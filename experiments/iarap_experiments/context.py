"""What every section of the report shares: the CLI, folders, mesh locations, mode and the claim ledger."""
from __future__ import annotations

import csv
import json
import os
import time
from dataclasses import dataclass, field

from .cli import Cli

METHODS = ["arap", "spokes-rims", "iarap"]
METHOD_LABELS = {"arap": "original ARAP", "spokes-rims": "spokes-and-rims", "iarap": "iARAP",
                 "iarap-refine": "iARAP, boundary refined"}


@dataclass
class Claim:
    section: str
    claim: str
    ours: str
    paper: str
    holds: str  # "yes", "no", "partly", "n/a" (with the reason in `ours`)


@dataclass
class Context:
    cli: Cli
    repo: str
    out: str  # report folder
    quick: bool  # reduced report (tests): small meshes, few iterations, bundled/generated meshes only
    shared_meshes: str | None  # ../shared/meshes when present (full report only)
    threads_all: int
    claims: list[Claim] = field(default_factory=list)
    render_jobs: list[dict] = field(default_factory=list)
    timings: dict = field(default_factory=dict)

    def path(self, *parts: str) -> str:
        full = os.path.join(self.out, *parts)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        return full

    def work(self, *parts: str) -> str:
        """Scratch files (meshes, constraints, CLI outputs) under DIR/work/."""
        return self.path("work", *parts)

    def data(self, name: str) -> str:
        return self.path("data", name)

    def shared(self, name: str) -> str | None:
        if self.shared_meshes is None:
            return None
        full = os.path.join(self.shared_meshes, name)
        return full if os.path.exists(full) else None

    def bundled(self, name: str) -> str:
        return os.path.join(self.repo, "data", name)

    def meshes_present(self, names: list[str]) -> list[tuple[str, str]]:
        """(name, path) of each shared mesh present (the bunny also from data/); the bunny only when quick."""
        if self.quick:
            return [("bunny.off", self.bundled("bunny.off"))]
        found = []
        for name in names:
            path = self.shared(name) or (self.bundled(name) if name == "bunny.off" else None)
            if path:
                found.append((name, path))
        return found

    def claim(self, section: str, claim: str, ours: str, paper: str, holds: str) -> None:
        self.claims.append(Claim(section, claim, ours, paper, holds))

    def write_json(self, name: str, value) -> str:
        full = self.data(name)
        with open(full, "w", encoding="utf-8") as f:
            json.dump(value, f, indent=1, default=float)
        return full

    def write_csv(self, name: str, header: list[str], rows: list[list]) -> str:
        full = self.data(name)
        with open(full, "w", newline="", encoding="utf-8") as f:
            writer = csv.writer(f)
            writer.writerow(header)
            writer.writerows(rows)
        return full


class Stopwatch:
    def __init__(self, ctx: Context, name: str):
        self.ctx, self.name = ctx, name

    def __enter__(self):
        self.start = time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.ctx.timings[self.name] = time.perf_counter() - self.start


def load_note(ctx: "Context") -> str:
    """'' on an idle machine, else a note that timings are disturbed (load average above the core count)."""
    load = os.getloadavg()[0]
    cores = os.cpu_count() or 1
    return f" (machine loaded: load average {load:.1f} on {cores} cores, timings unreliable)" if load > cores else ""


def yes_no(value: bool) -> str:
    return "yes" if value else "no"


def fmt(value: float, digits: int = 3) -> str:
    if value is None:
        return "-"
    if value == 0:
        return "0"
    if abs(value) >= 1e4 or abs(value) < 1e-3:
        return f"{value:.{max(digits - 1, 1)}e}"
    return f"{value:.{digits}g}"
