"""Thin wrappers around the `iarap` command-line tool: every measurement of the report goes through it."""
from __future__ import annotations

import json
import os
import subprocess
from dataclasses import dataclass


class CliError(RuntimeError):
    """The CLI failed; the message holds the command line and its stderr."""


@dataclass
class Cli:
    path: str  # the built `iarap` binary

    def run_json(self, args: list[str], timeout: float = 600, ok_codes: tuple = (0,)) -> dict:
        command = [self.path] + args
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
        if done.returncode not in ok_codes:
            raise CliError(f"{' '.join(command)} exited with {done.returncode}:\n{done.stderr.strip()}")
        try:
            return json.loads(done.stdout)
        except json.JSONDecodeError as error:
            raise CliError(f"{' '.join(command)}: stdout is not JSON ({error}):\n{done.stdout[:400]}") from error

    def help_text(self, subcommand: str) -> str:
        done = subprocess.run([self.path, subcommand, "--help"], capture_output=True, text=True, timeout=60)
        return done.stdout + done.stderr

    def info(self, mesh: str) -> dict:
        """The mesh check; exit code 1 (mesh not usable for ARAP) still prints the report ("usable": false)."""
        return self.run_json(["info", mesh, "--json"], ok_codes=(0, 1))

    def intrinsic(self, mesh: str, out_edges: str | None = None, refine_boundary: bool = False,
                  threads: int = 0, subdivide: int = 0) -> dict:
        args = ["intrinsic", mesh, "--json", "--threads", str(threads)]
        if subdivide:
            args += ["--subdivide", str(subdivide)]
        if out_edges:
            args += ["--out-edges", out_edges]
        if refine_boundary:
            args.append("--refine-boundary")
        return self.run_json(args)

    def deform(self, mesh: str, out: str, method: str, iterations: int, constraints: str | None = None,
               scenario: str | None = None, tolerance: float = 0.0, threads: int = 0,
               extra: list[str] | None = None) -> dict:
        """One `iarap deform` run; tolerance 0 runs every iteration unless the energy reaches exactly 0."""
        args = ["deform", mesh, "--method", method, "--iterations", str(iterations), "--tolerance",
                repr(tolerance), "--threads", str(threads), "--out", out, "--json", "--quiet",
                "--pin-unconstrained"]
        if constraints:
            args += ["--constraints", constraints]
        if scenario:
            args += ["--scenario", scenario]
        extra = list(extra or [])
        # `iarap` alone is the paper's discretization here; the CLI's default refines obtuse boundary edges
        # (issue 8), which the report runs as its own variant with `--boundary refine`.
        if method == "iarap" and "--boundary" not in extra and self.has_boundary_option():
            extra += ["--boundary", "paper"]
        # The paper's algorithm is plain local/global; the CLI's default accelerates it (issue 17).
        if "--accel" not in extra and self.has_option("deform", "--accel"):
            extra += ["--accel", "none"]
        return self.run_json(args + extra)

    def has_option(self, subcommand: str, option: str) -> bool:
        if not hasattr(self, "_help"):
            self._help = {}
        if subcommand not in self._help:
            self._help[subcommand] = self.help_text(subcommand)
        return option in self._help[subcommand]

    def has_boundary_option(self) -> bool:
        if not hasattr(self, "_has_boundary"):
            self._has_boundary = "--boundary" in self.help_text("deform")
        return self._has_boundary

    def bench(self, meshes: list[str], threads: int, iterations: int, subdivide: int = 0,
              methods: list[str] | None = None) -> dict:
        args = ["bench", *meshes, "--json", "--threads", str(threads), "--iterations", str(iterations),
                "--subdivide", str(subdivide)]
        methods = list(methods or ["arap", "spokes-rims", "iarap"])
        # Time the paper's iARAP under its own name (the CLI's `iarap` refines obtuse boundary edges).
        paper = self.has_boundary_option()
        if paper:
            methods = ["iarap-paper" if m == "iarap" else m for m in methods]
        args += ["--methods", ",".join(methods)]
        result = self.run_json(args, timeout=900)
        if paper:
            for row in result.get("results", []):
                if row.get("method") == "iarap-paper":
                    row["method"] = "iarap"
        return result

    def laplacian_properties(self, mesh: str) -> list:
        return self.run_json(["laplacian", mesh, "--properties", "--json"])

    def laplacian_matrix(self, mesh: str, kind: str, out: str) -> str:
        """Writes the operator as Matrix Market; returns the path."""
        command = [self.path, "laplacian", mesh, "--kind", kind, "--out", out]
        done = subprocess.run(command, capture_output=True, text=True, timeout=600)
        if done.returncode != 0:
            raise CliError(f"{' '.join(command)} exited with {done.returncode}:\n{done.stderr.strip()}")
        return out

    def has_subcommand(self, name: str) -> bool:
        done = subprocess.run([self.path, "--help"], capture_output=True, text=True, timeout=60)
        return any(line.split()[:1] == [name] for line in done.stdout.splitlines())


def find_cli(repo_root: str) -> str:
    """The CLI to drive: $IARAP_CLI, else build/iarap, else the newest build*/iarap of the checkout."""
    explicit = os.environ.get("IARAP_CLI")
    if explicit:
        return explicit
    default = os.path.join(repo_root, "build", "iarap")
    if os.path.exists(default):
        return default
    candidates = [os.path.join(repo_root, d, "iarap") for d in os.listdir(repo_root) if d.startswith("build")]
    candidates = [c for c in candidates if os.path.isfile(c) and os.access(c, os.X_OK)]
    if not candidates:
        raise CliError(f"no built iarap CLI under {repo_root}/build*/ (run `bash scripts/build.sh`)")
    return max(candidates, key=os.path.getmtime)
