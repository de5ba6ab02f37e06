"""The solve options are one schema (include/iarap/solver/solve_option_fields.h, iarap.SOLVE_OPTIONS): every
front-end offers every option under its name with the schema's default, docs/options.md lists each one the
way the front-ends spell it, and a bad value gets the same message from the command line, Python, the HTTP
server and a batch manifest."""
import ast
import json
import math
import re
import subprocess
import urllib.error
import urllib.request

import numpy as np
import pytest

import iarap
from iarap import batch

from conftest import REPO, handle_scene

OPTIONS = {option["name"]: option for option in iarap.SOLVE_OPTIONS}
BAD_TOLERANCE = "tolerance must be a finite number; got nan"


def signature(function):
    """{keyword: default} of a binding from the signature on the first line of its docstring."""
    line = function.__doc__.splitlines()[0]
    args = ast.parse(f"def {line}: pass").body[0].args
    positional = args.posonlyargs + args.args
    defaults = [None] * (len(positional) - len(args.defaults)) + list(args.defaults)
    pairs = list(zip(positional, defaults)) + list(zip(args.kwonlyargs, args.kw_defaults))
    return {a.arg: None if d is None else ast.literal_eval(d) for a, d in pairs}


def test_the_schema_names_every_option_once():
    assert list(OPTIONS)[:6] == ["iterations", "tolerance", "accelerator", "window", "gradient_tolerance",
                                 "time_budget_ms"]
    assert len({o["flag"] for o in iarap.SOLVE_OPTIONS}) == len(OPTIONS)
    for option in iarap.SOLVE_OPTIONS:
        assert option["flag"].startswith("--") and option["doc"] and option["range"], option


@pytest.mark.parametrize("function, defaults", [
    (iarap.ARAP.solve, {}),
    (iarap.Simulation.__init__, {"iterations": 100, "tolerance": 1e-10}),  # default_step_options()
    (iarap.parameterize, {"iterations": 100}),  # default_param_solve_options()
    (iarap.deform_file, {}),
])
def test_python_takes_every_option_with_its_default_and_doc(function, defaults):
    keywords = signature(function)
    for name, option in OPTIONS.items():
        assert name in keywords, f"{function.__qualname__} lacks {name}"
        assert keywords[name] == defaults.get(name, option["default"]), name
        assert f"{name}: {option['doc']} ({option['range']}" in function.__doc__, name


@pytest.mark.parametrize("command", ["deform", "simulate", "param"])
def test_the_command_line_takes_every_option(cli, command):
    help_text = subprocess.run([cli, command, "--help"], capture_output=True, text=True, check=True).stdout
    for option in iarap.SOLVE_OPTIONS:
        assert re.search(rf"^\s+{option['flag']} \w+:{re.escape(option['range'])}=", help_text, re.M), \
            f"{command} --help lacks {option['flag']}:\n{help_text}"


@pytest.fixture(scope="module")
def server(cli):
    """A running `iarap serve` without a mesh: the request parsing answers before any session work."""
    process = subprocess.Popen([cli, "serve", "--port", "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    line = process.stdout.readline()
    match = re.search(r"http://[\w.]+:\d+/", line)
    if not match:
        process.kill()
        pytest.fail(f"iarap serve printed no URL: {line!r} {process.stderr.read()}")
    yield match.group(0)
    process.terminate()
    process.wait(timeout=10)


def post_error(url, body, route="api/solve"):
    request = urllib.request.Request(url + route, data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request, timeout=30)
    return refused.value.code, json.loads(refused.value.read())["error"]


@pytest.mark.parametrize("route", ["api/solve", "api/param"])
def test_the_server_accepts_every_option_by_name(server, route):
    status, message = post_error(server, {"no_such_option": 1}, route)
    assert status == 400
    accepted = message.split("; expected ")[1].split(", ")
    assert set(OPTIONS) <= set(accepted), message


def test_docs_table_lists_every_option_as_the_front_ends_spell_it():
    text = (REPO / "docs" / "options.md").read_text()
    rows = {cells[0]: cells for cells in
            ([c.strip() for c in line.strip().strip("|").split("|")] for line in text.splitlines()
             if line.startswith("| ")) if cells[0] in OPTIONS}
    for name, option in OPTIONS.items():
        assert name in rows, f"docs/options.md has no row for {name}"
        _, flag, keyword, field, manifest, default, value_range, unit, doc = rows[name]
        assert (flag, keyword, field, manifest) == (f"`{option['flag']}`", f"`{name}`", f"`{name}`", f"`{name}`")
        assert default == str(option["default"]) if isinstance(option["default"], str) else \
            float(default) == option["default"], name
        assert (value_range, unit, doc) == (option["range"], option["unit"], option["doc"]), name


def test_batch_manifests_take_every_option_as_a_field(tmp_path):
    values = {"iterations": 7, "tolerance": 1e-08, "accelerator": "lbfgs", "window": 3,
              "gradient_tolerance": 0.5, "time_budget_ms": 250.0}
    job = {"mesh": str(REPO / "data" / "bunny.off"), "output": str(tmp_path / "o.obj"),
           "scenario": str(REPO / "data" / "bunny_scenario.json")}
    job.update({name: values.get(name, option["default"]) for name, option in OPTIONS.items()})
    (tmp_path / "jobs.json").write_text(json.dumps([job]))
    argv = batch.read_manifest(tmp_path / "jobs.json")[0].argv("iarap")
    for name, option in OPTIONS.items():
        assert argv[argv.index(option["flag"]) + 1] == str(job[name]), name
    # param runs on the same engine: the same fields become the same flags.
    param = {"mesh": job["mesh"], "output": str(tmp_path / "uv.obj"), "command": "param"}
    param.update({name: job[name] for name in OPTIONS})
    (tmp_path / "param.json").write_text(json.dumps([param]))
    argv = batch.read_manifest(tmp_path / "param.json")[0].argv("iarap")
    for name, option in OPTIONS.items():
        assert argv[argv.index(option["flag"]) + 1] == str(param[name]), name


def test_a_bad_tolerance_gets_one_message_everywhere(cli, server, tmp_path):
    V, F = iarap.read_mesh(REPO / "data" / "bunny.off")
    solver = iarap.ARAP(V, F, fixed=[0, 1, 2])
    with pytest.raises(iarap.InputError) as python:
        solver.solve(V[[0, 1, 2]], tolerance=math.nan)
    assert str(python.value) == BAD_TOLERANCE
    with pytest.raises(iarap.InputError, match=re.escape(BAD_TOLERANCE)):
        iarap.Simulation(V, F, [0, 1, 2], dt=0.1, tolerance=np.float64("nan"))
    with pytest.raises(ValueError, match=re.escape("gradient_tolerance must be a finite number >= 0; got -1")):
        iarap.Simulation(V, F, [0, 1, 2], dt=0.1, gradient_tolerance=-1)
    with pytest.raises(ValueError, match=re.escape("accelerator must be one of newton, hybrid, lbfgs, anderson, none; got 2")):
        solver.solve(V[[0, 1, 2]], accelerator=2)

    run = subprocess.run([cli, "deform", REPO / "data" / "bunny.off", "--scenario",
                          REPO / "data" / "bunny_scenario.json", "--out", tmp_path / "o.obj", "--tolerance", "nan"],
                         capture_output=True, text=True)
    assert run.returncode == 2 and f"--tolerance: {BAD_TOLERANCE}" in run.stderr, run.stderr

    assert post_error(server, {"tolerance": "nan"}) == (400, 'tolerance must be a finite number; got "nan"')
    assert post_error(server, {"tolerance": "nan"}, "api/param") == \
        (400, 'tolerance must be a finite number; got "nan"')
    with pytest.raises(iarap.InputError, match=re.escape(BAD_TOLERANCE)):
        iarap.parameterize(V, F, tolerance=math.nan)
    assert post_error(server, {"gradient_tolerance": -1}) == \
        (400, "gradient_tolerance must be a finite number >= 0; got -1")

    job = {"mesh": str(REPO / "data" / "bunny.off"), "output": str(tmp_path / "b.obj"),
           "scenario": str(REPO / "data" / "bunny_scenario.json"), "tolerance": math.nan}
    (tmp_path / "jobs.json").write_text(json.dumps([job]))
    failed = batch.run_job(batch.read_manifest(tmp_path / "jobs.json")[0], str(cli))  # a usage error: no retry
    assert failed["status"] == "failed" and f"--tolerance: {BAD_TOLERANCE}" in failed["error"], failed


def test_the_python_report_has_every_documented_field():
    """ARAP.report is written by visit_arap_report: every field docs/options.md names is in it."""
    text = (REPO / "docs" / "options.md").read_text()
    fields = re.findall(r"`([a-z_]+)`", text[text.index("Its fields are"):text.index("; `iarap deform` adds")])
    V, F = iarap.read_mesh(REPO / "data" / "bunny.off")
    solver = iarap.ARAP(V, F, fixed=[0, 1, 2])
    solver.solve(V[[0, 1, 2]], iterations=2)
    assert len(fields) > 20 and set(fields) <= set(solver.report), sorted(set(fields) - set(solver.report))


def test_newton_trust_radius_bounds_the_first_newton_step():
    """A trust radius far below the first step's length holds Newton to a sliver of its free decrease."""
    V, F = iarap.read_mesh(REPO / "data" / "bunny.off")
    fixed, targets = handle_scene(V)
    solver = iarap.ARAP(V, F, fixed=fixed)
    decrease = {}
    for radius in (0.0, 1e-9):
        solver.solve(targets, iterations=1, tolerance=-1, accelerator="newton", newton_trust_radius=radius)
        decrease[radius] = solver.report["initial_energy"] - solver.report["energies"][0]
    assert 0 < decrease[1e-9] < 1e-3 * decrease[0.0], decrease
