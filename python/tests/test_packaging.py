"""`pip install .` and `python3 -m build --wheel` give a self-contained, typed package.

Both reuse the CMake build tree the tests import the package from (IARAP_CMAKE_BUILD_DIR, see setup.py), so
they cost a venv and a copy, not a compile: the build itself is what the rest of the suite tests. They run
on a copy of the files the Python build reads (pyproject.toml, setup.py, VERSION, python/), so that the
checkout gets no build-python/ or *.egg-info.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import zipfile

import pytest

import iarap
from conftest import REPO, build_dir

VERSION = (REPO / "VERSION").read_text().strip()


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    if build_dir() is None:
        pytest.skip("the package was not imported from a CMake build tree")
    root = tmp_path_factory.mktemp("source")
    for name in ("pyproject.toml", "setup.py", "VERSION", "LICENSE"):
        shutil.copy(REPO / name, root / name)
    shutil.copytree(REPO / "python" / "iarap", root / "python" / "iarap")
    shutil.copy(REPO / "python" / "README.md", root / "python" / "README.md")
    return root


def clean_env(**extra):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LD_LIBRARY_PATH")}
    env["IARAP_CMAKE_BUILD_DIR"] = str(build_dir())
    env.update(extra)
    return env


def needed_libraries(extension):
    dynamic = subprocess.run(["readelf", "-d", str(extension)], capture_output=True, text=True, check=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[(.*)\]", dynamic)


def test_pip_install_into_a_venv(source, tmp_path):
    venv = tmp_path / "venv"
    # Without its own pip: the venv runs Debian's (a system site package), which installs into the venv.
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    install = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index",
                              "--no-deps", str(source)], capture_output=True, text=True, env=clean_env(),
                             timeout=600, cwd=tmp_path)
    assert install.returncode == 0, install.stdout + install.stderr
    code = ("import iarap, numpy as np, pathlib; V, F = iarap.read_mesh(pathlib.Path('bunny.off')); "
            "s = iarap.ARAP(V, F, fixed=[0, 1, 2]); U = s.solve(V[[0, 1, 2]], iterations=2); "
            "print(iarap.__file__, iarap.__version__, float(abs(U - V).max()))")
    shutil.copy(REPO / "data" / "bunny.off", tmp_path / "bunny.off")
    run = subprocess.run([str(python), "-c", code], cwd=tmp_path, capture_output=True, text=True,
                         env=clean_env(), timeout=300)
    assert run.returncode == 0, run.stderr
    file, version, moved = run.stdout.split()
    package = pathlib.Path(file).parent
    assert package.parent.name == "site-packages" and venv in package.parents  # the venv's copy, not build/
    assert version == VERSION
    assert float(moved) < 1e-9  # targets at rest: the rest shape is the solution (round-off of 2 solves)
    assert (package / "py.typed").exists() and (package / "__init__.pyi").exists()
    extensions = list(package.glob("_core*.so"))
    assert len(extensions) == 1
    assert not any("iarap" in lib for lib in needed_libraries(extensions[0]))  # the library is inside


def test_wheel(source, tmp_path):
    pytest.importorskip("build", reason="Debian's python3-build is not installed")
    run = subprocess.run([sys.executable, "-m", "build", "--wheel", "--no-isolation", "--outdir", str(tmp_path),
                          str(source)], capture_output=True, text=True, env=clean_env(), timeout=600,
                         cwd=tmp_path)  # not the checkout, whose build/ folder would shadow the module build
    assert run.returncode == 0, run.stdout + run.stderr
    wheels = list(tmp_path.glob("iarap-*.whl"))
    assert len(wheels) == 1 and wheels[0].name.startswith(f"iarap-{VERSION}-")
    names = zipfile.ZipFile(wheels[0]).namelist()
    for expected in ("iarap/__init__.py", "iarap/__init__.pyi", "iarap/py.typed"):
        assert expected in names
    assert len([n for n in names if re.match(r"iarap/_core\..*\.so$", n)]) == 1
    metadata = zipfile.ZipFile(wheels[0]).read(f"iarap-{VERSION}.dist-info/METADATA").decode()
    assert f"Version: {VERSION}" in metadata and "Requires-Dist: numpy" in metadata
