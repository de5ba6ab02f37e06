"""iarap.batch on a local Dask cluster of 2 workers: outputs bitwise those of sequential `iarap deform`
runs, a failing job reported while the others finish, a rerun skipping finished jobs, a worker killed
mid-run, jobs the tool refuses failing once (one line, no traceback) while killed ones are retried, and
manifest errors naming the file and job."""
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")
from iarap import batch  # noqa: E402

DATA = Path(__file__).resolve().parents[2] / "data"


def deform_jobs(tmp_path, count, extra=()):
    """count deform jobs over the bundled bunny: the three methods, scenario and constraints files."""
    jobs = []
    for k in range(count):
        entry = {"mesh": str(DATA / "bunny.off"), "method": ["arap", "spokes-rims", "iarap"][k % 3],
                 "output": str(tmp_path / "out" / f"job{k}.obj"), "args": ["--iterations", str(5 + k % 4), *extra]}
        if k % 2:
            entry["constraints"] = str(DATA / "bunny_constraints.txt")
        else:
            entry["scenario"] = str(DATA / "bunny_scenario.json")
        jobs.append(entry)
    return jobs


def write_manifest(tmp_path, jobs, name="jobs.json"):
    path = tmp_path / name
    path.write_text(json.dumps(jobs))
    return path


def sequential_outputs(cli, jobs, tmp_path):
    cli = str(cli)
    """The same command lines run one after the other: the reference bytes."""
    reference = {}
    for job in jobs:
        out = tmp_path / "sequential" / Path(job.output).name
        out.parent.mkdir(exist_ok=True)
        argv = job.argv(cli)
        argv[argv.index("--out") + 1] = str(out)
        subprocess.run(argv, check=True, capture_output=True)
        reference[job.output] = out.read_bytes()
    return reference


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_outputs_equal_sequential_runs_and_failures_are_contained(cli, tmp_path, client):
    entries = deform_jobs(tmp_path, 6)
    entries.append({"mesh": str(DATA / "bunny.off"), "constraints": str(tmp_path / "missing.txt"),
                    "output": str(tmp_path / "out" / "broken.obj")})
    manifest = write_manifest(tmp_path, entries)
    jobs = batch.read_manifest(manifest)
    results = batch.run_batch(manifest, cli=cli, client=client, progress=None)
    assert [r["status"] for r in results] == ["done"] * 6 + ["failed"]
    assert "missing.txt" in results[-1]["error"]
    assert not os.path.exists(tmp_path / "out" / "broken.obj")
    reference = sequential_outputs(cli, jobs[:6], tmp_path)
    for job in jobs[:6]:
        assert Path(job.output).read_bytes() == reference[job.output], job.name
        record = json.loads(Path(job.output + ".batch.json").read_text())
        assert record["report"]["vertices"] == 3485
    # A rerun skips what is finished; the broken job is tried (and fails) again.
    again = batch.run_batch(manifest, cli=cli, client=client, progress=None)
    assert [r["status"] for r in again] == ["skipped"] * 6 + ["failed"]
    # A changed job (other iterations) is not mistaken for a finished one.
    entries[0]["args"] = ["--iterations", "9"]
    write_manifest(tmp_path, entries)
    third = batch.run_batch(manifest, cli=cli, client=client, progress=None)
    assert third[0]["status"] == "done" and third[1]["status"] == "skipped"


def test_a_worker_killed_mid_run(cli, tmp_path, client):
    # 12 jobs of ~0.3-1 s each (plain iterations) on 2 workers; one worker is killed once jobs are running.
    jobs_entries = deform_jobs(tmp_path, 12, extra=("--accel", "none"))
    for e in jobs_entries:
        e["args"][1] = "200"
    manifest = write_manifest(tmp_path, jobs_entries)
    outcome = {}
    runner = threading.Thread(target=lambda: outcome.update(
        results=batch.run_batch(manifest, cli=cli, client=client, progress=None)))
    started = time.perf_counter()
    runner.start()
    while not list((tmp_path / "out").glob("*.batch.json")) and time.perf_counter() - started < 120:
        time.sleep(0.05)
    victim = next(iter(client.run(os.getpid).values()))
    os.kill(victim, signal.SIGKILL)
    runner.join(timeout=300)
    assert not runner.is_alive()
    results = outcome["results"]
    # A job the killed worker had finished may come back as "skipped": Dask resubmits it (its result died
    # with the worker) and the rerun finds its record. None fails, and every output is the sequential one.
    assert all(r["status"] in ("done", "skipped") for r in results), results
    jobs = batch.read_manifest(manifest)
    reference = sequential_outputs(cli, jobs, tmp_path)
    for job in jobs:
        assert Path(job.output).read_bytes() == reference[job.output], job.name


def counting_cli(tmp_path, cli):
    """A stand-in for the tool that logs each command line it gets, and dies by SIGKILL (as a crash or the
    out-of-memory killer would end it) when its arguments name "crash"; otherwise it runs the tool."""
    script = tmp_path / "iarap-counting"
    script.write_text(f"""#!/bin/sh
echo "$*" >> '{tmp_path / "calls.log"}'
case "$*" in *crash*) kill -9 $$ ;; esac
exec '{cli}' "$@"
""")
    script.chmod(0o755)
    return script


def calls(tmp_path, output):
    """How many times the tool was started for the job writing `output`."""
    return sum(f"--out {output} " in line for line in (tmp_path / "calls.log").read_text().splitlines())


def doomed_jobs(tmp_path):
    """A missing mesh (the tool's exit 2) and a mesh param cannot cut into disks (three triangles on one edge:
    exit 1), beside a job that works."""
    (tmp_path / "fin.off").write_text("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                      "3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    return [{"mesh": str(tmp_path / "missing.off"), "scenario": str(DATA / "bunny_scenario.json"),
             "output": str(tmp_path / "out" / "missing.obj")},
            {"command": "param", "mesh": str(tmp_path / "fin.off"), "output": str(tmp_path / "out" / "closed.obj")},
            deform_jobs(tmp_path, 1)[0]]


def test_jobs_the_tool_refuses_fail_once_and_crashes_are_retried(cli, tmp_path, client):
    entries = doomed_jobs(tmp_path) + [dict(deform_jobs(tmp_path, 1)[0], output=str(tmp_path / "out" / "crash.obj"))]
    results = batch.run_batch(write_manifest(tmp_path, entries), cli=counting_cli(tmp_path, cli), client=client,
                              progress=None, retries=1)
    assert [r["status"] for r in results] == ["failed", "failed", "done", "failed"], results
    assert results[0]["error"].startswith("missing.obj: ") and "missing.off" in results[0]["error"]
    assert results[1]["error"].startswith("closed.obj: ") and "cannot be cut into disk charts" in results[1]["error"]
    assert results[3]["error"] == "crash.obj: killed by signal 9"
    # Refused: tried once, whatever `retries` says. Killed: tried again (1 + retries).
    assert [calls(tmp_path, e["output"]) for e in entries] == [1, 1, 1, 2]


def test_a_refused_job_is_one_line_without_traceback(cli, tmp_path):
    manifest = write_manifest(tmp_path, doomed_jobs(tmp_path))
    run = subprocess.run([sys.executable, "-m", "iarap.batch", str(manifest), "--workers", "1", "--cli",
                          str(counting_cli(tmp_path, cli))], capture_output=True, text=True, timeout=300,
                         env=dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(batch.__file__))))
    assert run.returncode == 1
    assert "Traceback" not in run.stderr, run.stderr
    failed = [line for line in run.stderr.splitlines() if "failed:" in line]
    assert len(failed) == 2, run.stderr
    assert failed[0].startswith("iarap batch: failed: missing.obj: ") and "missing.off" in failed[0]
    assert failed[1].startswith("iarap batch: failed: closed.obj: iarap: error: ")
    assert "1 done, 0 skipped, 2 failed" in run.stderr


@pytest.mark.parametrize("entry, says", [
    ({"mesh": "a.off"}, "'output' is missing"),
    ({"mesh": "a.off", "output": "b.obj", "colour": 1}, "unknown field"),
    ({"mesh": "a.off", "output": "b.obj"}, "exactly one of 'scenario' and 'constraints'"),
    ({"mesh": "a.off", "output": "b.obj", "scenario": "s.json", "constraints": "c.txt"}, "exactly one"),
    ({"mesh": "a.off", "output": "b.obj", "command": "simulate"}, "not one of deform, param"),
    ({"mesh": "a.off", "output": "b.obj", "command": "param", "args": ["--out", "x"]}, "may not set --out"),
    ({"mesh": "a.off", "output": "a.off", "command": "param"}, "the output is the input mesh"),
    ({"mesh": "a.off", "output": "b.obj", "scenario": "s.json", "rigid": 3}, "'rigid' is the path of a file"),
    ({"mesh": "a.off", "output": "b.obj", "scenario": "s.json", "volume": "yes"}, "'volume' is true or false"),
    ({"mesh": "a.off", "output": "b.obj", "command": "param", "rigid": "g.txt"}, "a param job takes no"),
    ({"mesh": "a.off", "output": "b.obj", "command": "param", "volume": True}, "a param job takes no"),
])
def test_manifest_errors_name_the_job(tmp_path, entry, says):
    manifest = write_manifest(tmp_path, [entry])
    with pytest.raises(batch.ManifestError, match=says) as error:
        batch.read_manifest(manifest)
    assert "jobs.json: job 0" in str(error.value)


def test_deform_files_and_volume_become_the_tools_options(tmp_path):
    """rigid, stiffness, forces: paths from the manifest's folder; volume: the switch (JSON and CSV)."""
    manifest = write_manifest(tmp_path, [{"mesh": "a.off", "output": "b.obj", "scenario": "s.json",
                                          "rigid": "g.txt", "stiffness": "/abs/s.txt", "forces": "f.txt",
                                          "volume": True}])
    [job] = batch.read_manifest(manifest)
    base = str(tmp_path.resolve())
    assert job.options == ("--scenario", f"{base}/s.json", "--rigid", f"{base}/g.txt", "--stiffness",
                           "/abs/s.txt", "--forces", f"{base}/f.txt", "--volume")
    (tmp_path / "jobs.csv").write_text("mesh,output,scenario,rigid,volume\na.off,b.obj,s.json,g.txt,false\n"
                                       "a.off,c.obj,s.json,,1\n")
    plain, solid = batch.read_manifest(tmp_path / "jobs.csv")
    assert plain.options == ("--scenario", f"{base}/s.json", "--rigid", f"{base}/g.txt")
    assert solid.options == ("--scenario", f"{base}/s.json", "--volume")


def test_csv_manifest_and_duplicate_outputs(tmp_path):
    (tmp_path / "jobs.csv").write_text("mesh,output,command,method\nbunny.off,a.obj,param,iarap\n"
                                       "bunny.off,a.obj,param,arap\n")
    with pytest.raises(batch.ManifestError, match=r"jobs.csv:3: the same output as .*jobs.csv:2"):
        batch.read_manifest(tmp_path / "jobs.csv")
    (tmp_path / "bad.json").write_text('[{"mesh": "a.off",\n "output": }]')
    with pytest.raises(batch.ManifestError, match=r"bad.json:2: malformed JSON"):
        batch.read_manifest(tmp_path / "bad.json")


def test_the_iarap_batch_command(cli, tmp_path):
    """`iarap batch MANIFEST` hands over to python -m iarap.batch with the tool as the jobs' executable."""
    manifest = write_manifest(tmp_path, deform_jobs(tmp_path, 2))
    run = subprocess.run([str(cli), "batch", str(manifest), "--workers", "1", "--json"], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert [r["status"] for r in json.loads(run.stdout)] == ["done", "done"]
    assert "2 done, 0 skipped, 0 failed" in run.stderr
    bad = subprocess.run([str(cli), "batch", str(tmp_path / "none.json")], capture_output=True, text=True)
    assert bad.returncode == 2 and "none.json: cannot read the manifest" in bad.stderr


def test_every_relative_path_of_a_job_is_from_the_manifests_folder(cli, tmp_path, monkeypatch):
    """mesh, output and the paths inside 'args' alike: the tool runs in the manifest's folder, wherever the
    batch was started from (here another folder), so a job means the same from every caller."""
    folder = tmp_path / "project"
    (folder / "meshes").mkdir(parents=True)
    (folder / "meshes" / "head.off").write_bytes((DATA / "bunny_head.off").read_bytes())
    manifest = write_manifest(folder, [{"mesh": "meshes/head.off", "output": "out/uv.obj", "command": "param",
                                        "iterations": 3, "args": ["--report", "out/report.json"]}])
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    [job] = batch.read_manifest(manifest)
    result = batch.run_job(job, str(cli))
    assert result["status"] == "done", result
    report = json.loads((folder / "out" / "report.json").read_text())
    assert report["iterations"] <= 3 and (folder / "out" / "uv.obj").is_file()
    assert not (elsewhere / "out").exists()
