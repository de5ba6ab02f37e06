#!/usr/bin/env bash
# Quick start, step 1: install dependencies, build, and run the main job on the bundled bunny.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
# The web viewer's three.js and the browser test's playwright-core, from web/package-lock.json.
if command -v npm >/dev/null; then npm ci --prefix web --no-audit --no-fund; fi
mkdir -p out
./build/iarap deform data/bunny.off --scenario data/bunny_scenario.json --method iarap \
  --iterations 50 --out out/bunny_iarap.off --report out/bunny_iarap.json
echo "setup: deformed mesh in out/bunny_iarap.off, report in out/bunny_iarap.json"
if ls build/python/iarap/_core*.so >/dev/null 2>&1; then
  echo "setup: Python package in build/python: PYTHONPATH=$PWD/build/python /usr/bin/python3 -c 'import iarap'"
  echo "setup: or install it: pip install --no-build-isolation . (README, Python)"
fi
