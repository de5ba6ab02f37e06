"""The type stubs python/iarap/__init__.pyi match the built module: mypy.stubtest (names, classes,
properties, in both directions), and every function's parameter names, kinds and defaults against the
signature pybind11 writes on the first line of each docstring (stubtest cannot read those)."""
import ast
import os
import pathlib
import subprocess
import types
import sys

import pytest

import iarap

STUB = pathlib.Path(iarap.__file__).with_name("__init__.pyi")


def stub_tree():
    return ast.parse(STUB.read_text())


def parameters(function):
    """[(name, kind, default or None)] of an ast.FunctionDef, without self; kind: "positional" or "keyword"."""
    args = function.args
    positional = args.posonlyargs + args.args
    defaults = [None] * (len(positional) - len(args.defaults)) + [ast.literal_eval(d) for d in args.defaults]
    out = [(a.arg, "positional", d) for a, d in zip(positional, defaults)]
    out += [(a.arg, "keyword", None if d is None else ast.literal_eval(d))
            for a, d in zip(args.kwonlyargs, args.kw_defaults)]
    return [p for p in out if p[0] != "self"]


def runtime_parameters(obj):
    """The parameters of a pybind11 function from its docstring's first line, 'name(a: T, *, b: T = 1) -> R'."""
    line = obj.__doc__.splitlines()[0]
    assert "(" in line, f"no signature in the docstring of {obj!r}: {line!r}"
    return parameters(ast.parse(f"def {line}: pass").body[0])


def stub_functions():
    """{qualified name: [ast.FunctionDef]} of the stub's functions and methods (overloads grouped),
    properties left out (stubtest checks them)."""
    found = {}
    tree = stub_tree()
    scopes = [("", tree.body)] + [(node.name + ".", node.body) for node in tree.body if isinstance(node, ast.ClassDef)]
    for prefix, body in scopes:
        for node in body:
            decorators = {getattr(d, "id", getattr(d, "attr", None)) for d in node.decorator_list} \
                if isinstance(node, ast.FunctionDef) else set()
            if isinstance(node, ast.FunctionDef) and not decorators & {"property", "setter"}:
                found.setdefault(prefix + node.name, []).append(node)
    return found


def public_runtime_names():
    # Submodules (iarap.batch, pure Python and typed inline) are attributes only once imported.
    return {name for name in dir(iarap) if not name.startswith("_")
            and not isinstance(getattr(iarap, name), types.ModuleType)} | {"__version__"}


def stub_module_names():
    names = set()
    for node in stub_tree().body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return {n for n in names if not n.startswith("_")} | {"__version__"}


def test_stub_names_match_the_module():
    imported = {"annotations", "os", "np", "npt", "scipy", "Any", "Literal", "overload"}
    assert stub_module_names() == public_runtime_names() - imported - {"_core"}


@pytest.mark.parametrize("qualified", sorted(stub_functions()))
def test_stub_signature_matches_the_module(qualified):
    target = iarap
    for part in qualified.split("."):
        target = getattr(target, part)
    expected = runtime_parameters(target)
    for overload in stub_functions()[qualified]:
        stub = parameters(overload)
        assert [(n, k) for n, k, _ in stub] == [(n, k) for n, k, _ in expected], qualified
        for (name, _, stub_default), (_, _, runtime_default) in zip(stub, expected):
            if stub_default is not None or runtime_default is None:
                assert stub_default == runtime_default, f"{qualified}({name}=...)"


def test_stubtest(tmp_path):
    pytest.importorskip("mypy.stubtest", reason="Debian's python3-mypy is not installed")
    config = tmp_path / "mypy.ini"
    # numpy ships its own stubs; scipy has none (its types are Any).
    config.write_text("[mypy]\n[mypy-scipy.*]\nignore_missing_imports = True\n")
    # pybind11 classes have the metaclass pybind11_type, an implementation detail a stub does not spell;
    # the allowlist entries cover that class-level difference only, the members are still checked.
    allowlist = tmp_path / "allowlist.txt"
    allowlist.write_text("iarap.ARAP\niarap.Simulation\n")
    env = dict(os.environ, PYTHONPATH=str(STUB.parent.parent), MYPY_CACHE_DIR=str(tmp_path / "cache"))
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "iarap", "--mypy-config-file", str(config),
                          "--allowlist", str(allowlist)],
                         capture_output=True, text=True, cwd=tmp_path, env=env, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
