"""`cmake --install` puts a module that imports without the build tree (it finds libiarap by RPATH)."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

from conftest import build_dir


def test_installed_module_imports(tmp_path):
    build = build_dir()
    if build is None or shutil.which("cmake") is None:
        pytest.skip("the module was not imported from a CMake build tree, or cmake is missing")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", str(build), "--prefix", str(prefix)], check=True, capture_output=True)
    modules = list(prefix.glob("lib/python3*/dist-packages/iarap*.so"))
    assert len(modules) == 1, list(prefix.rglob("*"))
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LD_LIBRARY_PATH")}
    env["PYTHONPATH"] = str(modules[0].parent)
    code = ("import iarap, numpy as np; V = np.eye(3); "
            "print(iarap.__file__); print(iarap.check_mesh(np.vstack([V, [[0, 0, 0]]]), "
            "[[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]])['usable'])")
    run = subprocess.run([sys.executable, "-c", code], env=env, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    module_path, usable = run.stdout.split()
    assert pathlib.Path(module_path).resolve() == modules[0].resolve()
    assert usable == "True"
