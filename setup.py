"""Builds the extension iarap._core with the project's own CMake build (see pyproject.toml).

The wheel then holds python/iarap/ (__init__.py, the stubs __init__.pyi, py.typed) and the extension,
which contains the whole C++ library (no libiarap.so beside it) and links only Debian's shared libraries
(CHOLMOD, OpenMP, the C++ runtime).

Environment:
  IARAP_CMAKE_BUILD_DIR  a configured CMake build tree of this checkout to reuse (its target iarap_python
                         is brought up to date and copied); it must be built for the running interpreter.
  CMAKE_ARGS             extra options for the configure step of a fresh build (e.g. compiler launchers).
  CMAKE_BUILD_PARALLEL_LEVEL  parallel jobs (default: all CPUs).
"""
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        reuse = os.environ.get("IARAP_CMAKE_BUILD_DIR")
        if reuse:
            build_dir = pathlib.Path(reuse).resolve()
            if not (build_dir / "CMakeCache.txt").exists():
                sys.exit(f"setup.py: IARAP_CMAKE_BUILD_DIR={reuse} is not a configured CMake build tree")
        else:
            build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
            self.configure(build_dir)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        self.spawn(["cmake", "--build", str(build_dir), "--target", "iarap_python", "-j", jobs])
        built = build_dir / "python" / "iarap" / ("_core" + suffix)
        if not built.exists():
            found = sorted(p.name for p in (build_dir / "python" / "iarap").glob("_core*"))
            sys.exit(f"setup.py: {built} was not built (found {found or 'nothing'}): the CMake build is for "
                     f"another Python than {sys.executable}, or pybind11 / the Python headers are missing")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)

    def configure(self, build_dir):
        args = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                f"-DPython3_EXECUTABLE={sys.executable}", "-DIARAP_BUILD_PYTHON=ON", "-DIARAP_BUILD_APP=OFF",
                "-DIARAP_BUILD_TESTS=OFF", "-DIARAP_BUILD_EXAMPLES=OFF", "-DIARAP_BUILD_BENCH=OFF"]
        if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
            args += ["-G", "Ninja"]
        args += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        self.spawn(args)


setup(ext_modules=[CMakeExtension("iarap._core")], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": "build-python"}})
