#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite:
#   1. the normal build (warnings as errors) and every CTest test (with MPI found, cli_mpi runs
#      the build on `mpirun -np 3 --oversubscribe`);
#   2. the same tests built with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/;
#      without MPI there: Open MPI's own allocations read as leaks);
#   3. each libFuzzer target briefly (build-fuzz/; FUZZ_SECONDS per target, default 20).
# Usage: scripts/test.sh        (from anywhere; exits non-zero on the first failure)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

jobs=$(nproc)
# Each phase's heading says how long the run has taken so far (a slow phase shows in the log).
phase() { echo "== $1 [$((SECONDS / 60)) min $((SECONDS % 60)) s in]"; }
scripts/install-deps.sh

phase "build (warnings as errors)"
# The Python package and its tests on Debian's python3 (the one install-deps.sh gave pybind11,
# numpy and pytest; another python3 earlier on PATH would have none of them).
cmake -S . -B build -G Ninja -DMOTIONGRAPH_WERROR=ON -DMOTIONGRAPH_TESTS=ON -DMOTIONGRAPH_BENCHMARKS=ON \
  -DMOTIONGRAPH_PYTHON=ON -DPython_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build -j "$jobs"
phase "tests"
ctest --test-dir build --output-on-failure -j "$jobs"

phase "tests under AddressSanitizer + UndefinedBehaviorSanitizer"
# No Python package there: a plain python cannot load an extension built with the sanitizers.
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DMOTIONGRAPH_WERROR=ON -DMOTIONGRAPH_PYTHON=OFF \
  -DMOTIONGRAPH_SANITIZE=address,undefined -DMOTIONGRAPH_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build build-asan -j "$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j "$jobs"

phase "fuzzing each parser for ${FUZZ_SECONDS:-20} s"
scripts/fuzz.sh "${FUZZ_SECONDS:-20}"

phase "all tests passed"
