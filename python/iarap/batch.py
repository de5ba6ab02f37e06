"""Batches of iarap jobs (deform, param) on local worker processes or a Dask distributed cluster.

    python3 -m iarap.batch MANIFEST [--scheduler tcp://HOST:8786] [--workers N] [--cli PATH]
    iarap.batch.run_batch("jobs.json", scheduler=None, workers=2)

A manifest is a JSON list of jobs (or {"jobs": [...]}) or a CSV file with a header row. A job:

    {"mesh": "bunny.off", "output": "out/bunny_iarap.obj",        # required
     "command": "deform",                                         # or "param"; default "deform"
     "scenario": "bunny_scenario.json" | "constraints": "c.txt",  # deform: one of them
     "method": "iarap",                                           # deform --method (param: --energy)
     "tolerance": 1e-8, "accelerator": "lbfgs",                   # solve options by name
     "args": ["--repair"]}                                        # further options of the command

The solve options of a deform or param job (iarap.SOLVE_OPTIONS: iterations, tolerance, accelerator, window,
gradient_tolerance, time_budget_ms; docs/options.md) are fields of their own, in a CSV manifest columns;
each becomes its command-line flag, and the tool checks its value.

Relative paths are relative to the manifest's folder. Each job runs the `iarap` command line tool in a
worker process with one thread (`--threads 1`), so its output is bitwise the output of the same
`iarap deform` run by hand; the tool writes it atomically. Dask does the scheduling (no job system of our
own): a job whose worker dies is resubmitted by the scheduler, a job whose tool process is killed or
crashes is retried once (`retries`), a job the tool refuses (exit code 1 or 2: a missing input, a mesh
param cannot flatten) fails at once with the tool's message, and the others go on. A finished job leaves `OUTPUT.batch.json` (its command line and
report) beside its output; a rerun skips jobs whose record matches the job, so an interrupted batch
resumes where it stopped.
"""
from __future__ import annotations

import argparse
import csv
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import uuid
from dataclasses import dataclass
from pathlib import Path
import collections.abc as _abc
from typing import Any

from . import SOLVE_OPTIONS

__all__ = ["Job", "JobCrashed", "ManifestError", "main", "read_manifest", "run_batch", "run_job"]

_SOLVE_FLAGS = {option["name"]: option["flag"] for option in SOLVE_OPTIONS}
# Deform's per-vertex files (paths from the manifest, like 'mesh') and its --volume switch.
_DEFORM_FILES = ("rigid", "stiffness", "forces")
_FIELDS = ({"mesh", "output", "command", "scenario", "constraints", "method", "args", "name", "volume"}
           | set(_DEFORM_FILES) | set(_SOLVE_FLAGS))
_COMMANDS = ("deform", "param")


class ManifestError(ValueError):
    """A manifest that cannot be read: names the file and the job."""


@dataclass(frozen=True)
class Job:
    name: str
    command: str
    mesh: str
    output: str
    options: tuple[str, ...] = ()
    # The manifest's folder: the tool runs there, so that a relative path in 'args' (--pins, --report,
    # --forces, ...) means what 'mesh' and 'output' mean, a path from the manifest.
    folder: str = ""

    def argv(self, cli: str) -> list[str]:
        return [cli, self.command, self.mesh, *self.options, "--out", self.output, "--threads", "1", "--quiet"]

    def key(self) -> str:
        """What identifies the job's result: its command line and the inputs' sizes and times."""
        inputs = [self.mesh] + [p for p in (os.path.join(self.folder, o) for o in self.options) if os.path.isfile(p)]
        stamp = [(p, os.stat(p).st_size, os.stat(p).st_mtime_ns) for p in inputs]
        text = json.dumps([self.command, self.mesh, self.options, self.output, stamp])
        return hashlib.sha256(text.encode()).hexdigest()


def _record_path(output: str) -> str:
    return output + ".batch.json"


def _job_from_entry(entry: dict[str, Any], where: str, base: Path) -> Job:
    if not isinstance(entry, dict):
        raise ManifestError(f"{where}: a job is an object with 'mesh' and 'output'")
    unknown = set(entry) - _FIELDS
    if unknown:
        raise ManifestError(f"{where}: unknown field(s) {sorted(unknown)}; known: {sorted(_FIELDS)}")
    for required in ("mesh", "output"):
        if not entry.get(required):
            raise ManifestError(f"{where}: '{required}' is missing")
    command = entry.get("command") or "deform"
    if command not in _COMMANDS:
        raise ManifestError(f"{where}: command '{command}' is not one of {', '.join(_COMMANDS)}")
    resolve = lambda p: str(p if Path(p).is_absolute() else base / p)  # noqa: E731
    options: list[str] = []
    if command == "deform":
        if bool(entry.get("scenario")) == bool(entry.get("constraints")):
            raise ManifestError(f"{where}: a deform job needs exactly one of 'scenario' and 'constraints'")
        kind = "scenario" if entry.get("scenario") else "constraints"
        options += [f"--{kind}", resolve(entry[kind])]
        for field in _DEFORM_FILES:
            if field in entry:
                if not isinstance(entry[field], str) or not entry[field]:
                    raise ManifestError(f"{where}: '{field}' is the path of a file (`iarap deform --{field}`)")
                options += [f"--{field}", resolve(entry[field])]
        volume = entry.get("volume", False)
        if isinstance(volume, str):  # a CSV cell
            volume = {"true": True, "1": True, "false": False, "0": False}.get(volume.strip().lower(), volume)
        if not isinstance(volume, bool):
            raise ManifestError(f"{where}: 'volume' is true or false; got {volume!r}")
        if volume:
            options.append("--volume")
    elif any(field in entry for field in ("scenario", "constraints", "volume", *_DEFORM_FILES)):
        raise ManifestError(f"{where}: a param job takes no scenario, constraints, rigid, stiffness, forces or "
                            "volume (deform's)")
    if entry.get("method"):
        options += ["--method" if command == "deform" else "--energy", str(entry["method"])]
    solve = [name for name in _SOLVE_FLAGS if name in entry]  # deform and param run on one engine
    for name in solve:  # str() of a float is its repr: the tool reads back the very number
        options += [_SOLVE_FLAGS[name], str(entry[name])]
    extra = entry.get("args") or []
    if isinstance(extra, str):
        extra = extra.split()
    if not isinstance(extra, list) or not all(isinstance(a, str) for a in extra):
        raise ManifestError(f"{where}: 'args' is a list of strings (or one string of blank-separated options)")
    if any(a in ("--out", "--threads") for a in extra):
        raise ManifestError(f"{where}: 'args' may not set --out or --threads (the batch sets them)")
    mesh, output = resolve(entry["mesh"]), resolve(entry["output"])
    if os.path.abspath(mesh) == os.path.abspath(output):
        raise ManifestError(f"{where}: the output is the input mesh")
    name = str(entry.get("name") or Path(output).name)
    return Job(name, command, mesh, output, tuple(options + extra), str(base))


def read_manifest(path: str | os.PathLike[str]) -> list[Job]:
    """The jobs of a JSON or CSV manifest; ManifestError names the file and the job at fault."""
    path = Path(path)
    base = path.resolve().parent
    try:
        text = path.read_text()
    except OSError as error:
        raise ManifestError(f"{path}: cannot read the manifest: {error.strerror}") from None
    if path.suffix.lower() == ".csv":
        rows = list(csv.DictReader(text.splitlines()))
        entries = [{k: v for k, v in row.items() if k and v} for row in rows]
        where = [f"{path}:{i + 2}" for i in range(len(rows))]
    else:
        try:
            data = json.loads(text)
        except json.JSONDecodeError as error:
            raise ManifestError(f"{path}:{error.lineno}: malformed JSON: {error.msg}") from None
        entries = data.get("jobs") if isinstance(data, dict) else data
        if not isinstance(entries, list):
            raise ManifestError(f"{path}: expected a list of jobs or {{\"jobs\": [...]}}")
        where = [f"{path}: job {i}" for i in range(len(entries))]
    if not entries:
        raise ManifestError(f"{path}: no jobs")
    jobs = [_job_from_entry(e, w, base) for e, w in zip(entries, where)]
    outputs: dict[str, str] = {}
    for job, w in zip(jobs, where):
        other = outputs.setdefault(os.path.abspath(job.output), w)
        if other != w:
            raise ManifestError(f"{w}: the same output as {other}: {job.output}")
    return jobs


def _write_atomically(path: str, text: str) -> None:
    folder = os.path.dirname(os.path.abspath(path))
    fd, temp = tempfile.mkstemp(dir=folder, prefix=".batch-")
    try:
        with os.fdopen(fd, "w") as out:
            out.write(text)
        os.replace(temp, path)
    except BaseException:
        os.unlink(temp)
        raise


def _finished(job: Job) -> bool:
    try:
        record = json.loads(Path(_record_path(job.output)).read_text())
    except (OSError, ValueError):
        return False
    return record.get("key") == job.key() and os.path.isfile(job.output)


# The tool's exit codes that say the job itself is wrong (app/command_registry.h): 1, an input or runtime
# error (a missing or unusable mesh, a closed mesh given to param); 2, a usage error. Running it again
# gives the same answer, so such a job fails at once. Any other end (killed by a signal, out of memory, a
# crash) may pass on another try or another worker, and is retried.
_PERMANENT_EXIT_CODES = (1, 2)


class JobCrashed(RuntimeError):
    """A job whose tool process ended without the tool's own verdict (a signal, a crash): Dask retries it."""


def _tool_message(run: subprocess.CompletedProcess[str]) -> str:
    """The tool's error line (its first line that says "error"), else its first line, else how it ended."""
    lines = run.stderr.strip().splitlines()
    errors = [line for line in lines if "error" in line]
    if errors or lines:
        return (errors or lines)[0]
    return f"killed by signal {-run.returncode}" if run.returncode < 0 else f"exit code {run.returncode}"


def run_job(job: Job, cli: str) -> dict[str, Any]:
    """Runs one job in this process (a Dask task). A job the tool refuses (exit 1 or 2) comes back as
    {"status": "failed", "error": "NAME: the tool's message"} without raising, so Dask does not retry it;
    JobCrashed is raised when the tool process ended otherwise (a signal, a crash), for Dask to retry."""
    if _finished(job):
        return {"name": job.name, "status": "skipped", "output": job.output}
    os.makedirs(os.path.dirname(os.path.abspath(job.output)), exist_ok=True)
    started = time.perf_counter()
    tool = os.path.abspath(cli) if os.sep in cli else cli  # it runs in the manifest's folder
    run = subprocess.run(job.argv(tool) + ["--json"], capture_output=True, text=True, cwd=job.folder or None)
    seconds = time.perf_counter() - started
    if run.returncode in _PERMANENT_EXIT_CODES:
        return {"name": job.name, "status": "failed", "output": job.output,
                "error": f"{job.name}: {_tool_message(run)}"}
    if run.returncode != 0:
        raise JobCrashed(f"{job.name}: {_tool_message(run)}")
    try:
        report = json.loads(run.stdout)
    except ValueError:
        report = None
    _write_atomically(_record_path(job.output), json.dumps(
        {"key": job.key(), "argv": job.argv(cli), "seconds": seconds, "report": report}, indent=1) + "\n")
    return {"name": job.name, "status": "done", "output": job.output, "seconds": seconds}


def _find_cli(cli: str | None) -> str:
    for candidate in (cli, os.environ.get("IARAP_CLI"), shutil.which("iarap")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    raise FileNotFoundError("the iarap command line tool was not found: pass cli=PATH (--cli) or set IARAP_CLI")


class _Progress:
    def __init__(self, total: int, stream) -> None:
        self.total, self.stream, self.started, self.count = total, stream, time.perf_counter(), 0

    def step(self, result: dict[str, Any]) -> None:
        self.count += 1
        if self.stream is None:
            return
        elapsed = time.perf_counter() - self.started
        rate = self.count / elapsed if elapsed > 0 else 0.0
        eta = (self.total - self.count) / rate if rate > 0 else float("inf")
        filled = int(30 * self.count / self.total)
        self.stream.write(f"\r[{'#' * filled}{'.' * (30 - filled)}] {self.count}/{self.total}  "
                          f"{rate:.2f} jobs/s  ETA {eta:.0f} s  {result['name']}: {result['status']}\033[K")
        if self.count == self.total:
            self.stream.write("\n")
        self.stream.flush()


def run_batch(manifest: str | os.PathLike[str] | _abc.Iterable[Job], *, scheduler: str | None = None,
              workers: int = 2, cli: str | None = None, retries: int = 1, progress=sys.stderr,
              client=None) -> list[dict[str, Any]]:
    """Runs the jobs; returns one result per job in manifest order: {"name", "status" ("done", "skipped"
    or "failed"), "output", and "seconds" or "error"}. scheduler: a Dask scheduler address; None starts a
    local cluster of `workers` single-threaded worker processes; client: an existing distributed.Client."""
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise ImportError("iarap batch runs on Dask: apt-get install python3-distributed") from None

    jobs = read_manifest(manifest) if isinstance(manifest, (str, os.PathLike)) else list(manifest)
    cli = _find_cli(cli)
    own_cluster = None
    if client is None:
        if scheduler:
            client = Client(scheduler)
        else:
            own_cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=":0")
            client = Client(own_cluster)
    try:
        run = uuid.uuid4().hex[:8]  # keys unique per run: a rerun must not get an earlier run's results
        futures = {client.submit(run_job, job, cli, retries=retries, pure=False, key=f"iarap-{run}-{i}-{job.name}"): i
                   for i, job in enumerate(jobs)}
        results: list[dict[str, Any] | None] = [None] * len(jobs)
        bar = _Progress(len(jobs), progress)
        for future in as_completed(futures):
            i = futures[future]
            result: dict[str, Any]
            try:
                result = future.result()
            except Exception as error:  # the job's own error, or the scheduler's after repeated worker deaths
                result = {"name": jobs[i].name, "status": "failed", "output": jobs[i].output, "error": str(error)}
            results[i] = result
            bar.step(result)
        return results  # type: ignore[return-value]
    finally:
        if own_cluster is not None:
            client.close()
            own_cluster.close()
        elif scheduler:
            client.close()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="iarap batch", description="Run a manifest of iarap jobs on local "
                                     "worker processes or a Dask cluster")
    parser.add_argument("manifest", help="JSON or CSV list of jobs (see python -m pydoc iarap.batch)")
    parser.add_argument("--scheduler", help="Dask scheduler address (tcp://host:8786); default: a local cluster")
    parser.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    parser.add_argument("--cli", help="the iarap tool (default: $IARAP_CLI, then iarap on PATH)")
    parser.add_argument("--retries", type=int, default=1, help="retries of a failed job (default 1)")
    parser.add_argument("--json", action="store_true", help="print the results as JSON on stdout")
    args = parser.parse_args(argv)
    if args.workers < 1 or args.retries < 0:
        parser.error("--workers must be >= 1 and --retries >= 0")
    try:
        results = run_batch(args.manifest, scheduler=args.scheduler, workers=args.workers, cli=args.cli,
                            retries=args.retries)
    except (ManifestError, FileNotFoundError, ImportError) as error:
        print(f"iarap batch: error: {error}", file=sys.stderr)
        return 2
    failed = [r for r in results if r["status"] == "failed"]
    for r in failed:
        print(f"iarap batch: failed: {r['error']}", file=sys.stderr)
    counts = {s: sum(r["status"] == s for r in results) for s in ("done", "skipped", "failed")}
    print(f"iarap batch: {counts['done']} done, {counts['skipped']} skipped, {counts['failed']} failed",
          file=sys.stderr)
    if args.json:
        print(json.dumps(results, indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
