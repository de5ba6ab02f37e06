#!/usr/bin/env bash
# The long fuzzing campaign (issue 47, item 4), not part of CI: every reader's mutation fuzzer and the
# read -> repair -> check -> three methods pipeline on the ASan + UBSan build (build-asan/, made as
# scripts/test.sh --sanitize makes it). CI's suite runs the same drivers on a bounded budget.
#   bash scripts/fuzz.sh [SECONDS_PER_READER] [PIPELINE_INPUTS]     (defaults: 60 and 10000)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
inputs=${2:-10000}
if [ ! -x build-asan/tests/iarap_tests ]; then
  IARAP_BUILD_DIR=build-asan bash scripts/build.sh -DIARAP_SANITIZE=ON -DIARAP_BUILD_PYTHON=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
fi
# halt_on_error: the first report stops the run with the input's trace; the driver saves the input.
export ASAN_OPTIONS=detect_leaks=0:halt_on_error=1:handle_sigill=1
IARAP_FUZZ_SECONDS=$seconds IARAP_FUZZ_PIPELINE_INPUTS=$inputs \
  build-asan/tests/iarap_tests --gtest_filter='Fuzz.*' 2>&1 | tee fuzz.log | grep -E "mutated inputs|inputs|OK|FAILED|PASSED"
echo "fuzz: full log in fuzz.log"
