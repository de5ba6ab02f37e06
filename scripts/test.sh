#!/usr/bin/env bash
# Quick start, step 2: build and run the whole test suite (C++ via CTest, Python via pytest).
# With CI=true or --sanitize it also runs the suite under AddressSanitizer + UBSan (build-asan/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
# Formatting first: an unformatted file fails in seconds, before the build.
bash scripts/check_format.sh
bash scripts/build.sh
# The web viewer's three.js and the browser test's playwright-core, from web/package-lock.json.
if command -v npm >/dev/null; then npm ci --prefix web --no-audit --no-fund; fi
ctest --test-dir build --output-on-failure -j"$(nproc)"
if [ -d python/tests ] && [ -n "$(ls build/python/iarap/_core*.so 2>/dev/null)" ]; then
  # Two workers when pytest-xdist is there (install_deps.sh installs it), a file to a worker so that a
  # module's fixtures (the experiments' report: 17 s) run once: 83 -> 56 s on two cores.
  xdist=()
  if /usr/bin/python3 -c 'import xdist' 2>/dev/null; then xdist=(-n "$(nproc)" --dist loadfile); fi
  PYTHONPATH="$PWD/build/python" /usr/bin/python3 -m pytest -q "${xdist[@]}" python/tests experiments/tests
fi
if [ "${CI:-}" = "true" ] || [ "${1:-}" = "--sanitize" ]; then
  # -g1: line tables are all a sanitizer report needs (-g0 compiles no faster). UBSan's checks and the
  # optimization levels there: cmake/iarap_sanitizers.cmake, docs/building.md (a fresh clone: 404 s).
  # The examples (a page of API calls each) run in the Release suite; the library paths they take run here
  # in the tests of registration and deformation (19 s of this run's tests saved).
  IARAP_BUILD_DIR=build-asan bash scripts/build.sh -DIARAP_SANITIZE=ON -DIARAP_BUILD_PYTHON=OFF -DIARAP_BUILD_EXAMPLES=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
  # The Release run above already covers the long loops over every shared mesh and the browser session;
  # under the sanitizers (several times slower) they would take most of CI's time without new coverage.
  # The packaging tests (install, .deb) check file layout and RPATHs, which the Release run covers.
  # Long loops of kernels that shorter tests also run under the sanitizers (bunny solves to a weight or
  # iteration count: 20-40 s each here) stay in the Release run only. So do the HTTP suites of soft fits and
  # rigid groups (bunny solves of 20-40 iterations per method: 24 and 37 s here); the server's request
  # parsing runs here in web_http, web_atlas_http and the serve tests, the solves in the solver tests.
  ASAN_OPTIONS=detect_leaks=0:handle_sigill=1 ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE packaging \
    -E 'SharedSurfaceMeshes|SharedMeshesGetOneVerdict|SharedDisksFlipFreeAtThePeersEnergy|BoundaryRefinementOnSharedMeshes|SharedMeshesWithBoundaryStayAtRest|EndsWherePlainDoesOnTheBentBunny|FewerIterationsThanPlainOnTheBunny|FiftyIterationsMatchThePlainIteration|WeightReproducesTheHardResult|SoftPointsConvergeToHardOnesAsTheWeightGrows|SmallWeightEndsBetweenRestAndHard|RestStabilityOnBunny|BenchConvergeReportsReachedOrStationaryRuns|BenchConvergeTimesTheHybridsSwitch|FaceCentroidsEndOnTheirTargetsWithEveryAccelerator|web_soft_fit_http|web_rigid_smoothing_http|web_browser'
fi
