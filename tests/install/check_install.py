#!/usr/bin/env python3
"""CTest driver: what `cmake --install` (or the Debian package from `cpack -G DEB`) puts works on its own.

    check_install.py install BUILD SOURCE WORK   installs BUILD into WORK/prefix, moves the prefix (so only
                                                 relative paths can work) and runs the installed tool
    check_install.py deb BUILD SOURCE WORK       builds the .deb with cpack, checks its metadata, unpacks it
                                                 with dpkg-deb and runs the tool from the unpacked tree

Runs `iarap --version`, `info`, `deform` and `serve` (one GET of the page, which must be the installed
copy) and imports the installed Python package; LD_LIBRARY_PATH and PYTHONPATH from the caller are dropped
and the working directory is a scratch folder, so nothing comes from the build or source tree. Exits 1
naming the first failed check.
"""
import glob
import json
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time
import urllib.request

MODE, BUILD, SOURCE, WORK = sys.argv[1], *map(pathlib.Path, sys.argv[2:5])
VERSION = (SOURCE / "VERSION").read_text().strip()
ENV = {k: v for k, v in os.environ.items() if k not in ("LD_LIBRARY_PATH", "PYTHONPATH")}


def fail(message):
    print(f"check_install ({MODE}): FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def run(*args, **kwargs):
    result = subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=WORK, env=ENV,
                            timeout=300, **kwargs)
    if result.returncode != 0:
        fail(f"{' '.join(map(str, args))} exited {result.returncode}:\n{result.stdout}\n{result.stderr}")
    return result.stdout


def cache_value(name):
    match = re.search(rf"^{name}:\w+=(.*)$", (BUILD / "CMakeCache.txt").read_text(), re.M)
    return match.group(1) if match else None


def installed_tree():
    """The root under which CMAKE_INSTALL_PREFIX's layout (bin/, lib/, share/) now lies."""
    if MODE == "install":
        first = WORK / "first-prefix"
        run("cmake", "--install", BUILD, "--prefix", first)
        moved = WORK / "moved-prefix"
        first.rename(moved)  # RPATHs and the web root must be relative to survive this
        return moved
    run("cpack", "-G", "DEB", "-B", WORK / "cpack", "--config", BUILD / "CPackConfig.cmake")
    debs = sorted((WORK / "cpack").glob("*.deb"))
    if len(debs) != 1:
        fail(f"expected one .deb, found {debs}")
    fields = run("dpkg-deb", "--field", debs[0])
    for needed in (f"Version: {VERSION}", "Package: iarap", "libcholmod"):
        if needed not in fields:
            fail(f"{debs[0].name} control fields lack {needed!r}:\n{fields}")
    run("dpkg-deb", "--extract", debs[0], WORK / "root")
    return WORK / "root" / cache_value("CMAKE_INSTALL_PREFIX").lstrip("/")


def check_runpath(binary, tree):
    """The installed binary's RUNPATH is relative ($ORIGIN...), never into the build tree."""
    dynamic = run("readelf", "-d", binary)
    paths = re.findall(r"\((?:RUNPATH|RPATH)\)\s+Library r(?:un)?path: \[(.*)\]", dynamic)
    if not paths or any(not p.startswith("$ORIGIN") for p in ":".join(paths).split(":")):
        fail(f"{binary} has RUNPATH {paths}, expected only $ORIGIN-relative entries")


def check_tool(tree):
    iarap = tree / "bin" / "iarap"
    check_runpath(iarap, tree)
    out = run(iarap, "--version")
    if out.strip() != f"iarap {VERSION}":
        fail(f"--version printed {out!r}, expected 'iarap {VERSION}'")
    info = json.loads(run(iarap, "info", "--json", SOURCE / "data" / "bunny.off"))
    if info["vertices"] != 3485 or info["faces"] != 6966:
        fail(f"info --json reported {info['vertices']} vertices, {info['faces']} faces")
    out_mesh = WORK / "bunny_deformed.off"
    report = json.loads(run(iarap, "deform", SOURCE / "data" / "bunny.off", "--scenario",
                            SOURCE / "data" / "bunny_scenario.json", "--iterations", "5", "--out", out_mesh,
                            "--json"))
    if not out_mesh.exists() or report["iterations"] != 5 and not report["converged"]:
        fail(f"deform wrote no mesh or stopped early: {report}")
    check_serve(iarap, tree)


def check_serve(iarap, tree):
    web = tree / "share" / "iarap" / "web"
    index = web / "index.html"
    if not index.exists():
        fail(f"{index} not installed")
    marker = f"<!-- installed copy {os.getpid()} -->"
    index.write_text(index.read_text() + marker)  # proves the server reads the installed page
    three = SOURCE / "web" / "node_modules" / "three" / "build" / "three.module.js"
    if three.exists():  # the page's three.js addons must be installed too (app/CMakeLists.txt lists them)
        for js in (SOURCE / "web" / "src").glob("*.js"):
            for addon in re.findall(r"from\s+'three/addons/([^']+)'", js.read_text()):
                if not (web / "node_modules" / "three" / "examples" / "jsm" / addon).exists():
                    fail(f"{js.name} imports three/addons/{addon}, which is not installed")
    server = subprocess.Popen([str(iarap), "serve", "--port", "0"], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, cwd=WORK, env=ENV)
    try:
        line = server.stdout.readline()
        match = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        if not match:
            fail(f"serve printed {line!r} and {server.stderr.read() if server.poll() is not None else ''}")
        base = f"http://127.0.0.1:{match.group(1)}"
        with urllib.request.urlopen(base + "/", timeout=30) as response:
            page = response.read().decode()
        if marker not in page:
            fail("GET / did not return the installed share/iarap/web/index.html")
        if three.exists():
            with urllib.request.urlopen(base + "/node_modules/three/build/three.module.js", timeout=30) as r:
                if r.status != 200:
                    fail("three.module.js is not served from the installed tree")
    finally:
        server.send_signal(signal.SIGTERM)
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
            fail("serve did not stop on SIGTERM")


def check_python(tree):
    """The installed package imports from the installed tree alone (the extension holds the library)."""
    if not (BUILD / "python" / "iarap").is_dir():
        return  # the build has no Python module
    packages = glob.glob(str(tree / "lib" / "python3*" / "dist-packages" / "iarap" / "__init__.py"))
    if len(packages) != 1:
        fail(f"expected one installed iarap package, found {packages}")
    package = pathlib.Path(packages[0]).parent
    for name in ("__init__.pyi", "py.typed"):
        if not (package / name).exists():
            fail(f"{name} not installed beside {packages[0]}")
    code = ("import iarap, numpy as np; V = np.eye(3); print(iarap.__file__, iarap.__version__, "
            "iarap.check_mesh(np.vstack([V, [[0, 0, 0]]]), [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]])['usable'])")
    env = dict(ENV, PYTHONPATH=str(package.parent))
    python = cache_value("Python3_EXECUTABLE") or sys.executable
    result = subprocess.run([python, "-c", code], capture_output=True, text=True, cwd=WORK, env=env, timeout=120)
    if result.returncode != 0:
        fail(f"import iarap from {package.parent} failed:\n{result.stderr}")
    file, version, usable = result.stdout.split()
    if pathlib.Path(file).resolve() != (package / "__init__.py").resolve() or version != VERSION or usable != "True":
        fail(f"installed package printed {result.stdout!r}")


def main():
    if WORK.exists():
        shutil.rmtree(WORK)
    WORK.mkdir(parents=True)
    start = time.monotonic()
    tree = installed_tree()
    check_tool(tree)
    check_python(tree)
    print(f"check_install ({MODE}): ok in {time.monotonic() - start:.1f} s ({tree})")


if __name__ == "__main__":
    main()
