#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: installs what is missing,
# builds, runs every unit and end-to-end test with CTest; then builds the same
# suite with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/) and
# runs it again, any sanitizer report failing its test (halt_on_error).
# RISKNAV_SKIP_SANITIZERS=1 skips the second pass (quick local runs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BUILD_DIR=${BUILD_DIR:-build}
# CTest starts the costliest tests first when it knows their cost; a fresh
# build dir does not, and its longest tests (30-70 s under the sanitizers)
# then start last and run alone at the end. The committed costs (one
# sanitizer run's seconds) seed a build dir that has none yet.
seed_costs() {
  local f="$1/Testing/Temporary/CTestCostData.txt"
  if [ ! -f "$f" ]; then
    mkdir -p "$(dirname "$f")"
    cp tests/ctest-cost-data.txt "$f"
  fi
}
seed_costs "$BUILD_DIR"
(cd "$BUILD_DIR" && ctest --output-on-failure -j"$(nproc)" --timeout 600)
if [ "${RISKNAV_SKIP_SANITIZERS:-0}" != "1" ]; then
  echo "== the same suite under ASan + UBSan =="
  BUILD_DIR=build-asan bash scripts/build.sh -DRISKNAV_SANITIZE=ON \
    -DRISKNAV_BUILD_BENCHMARKS=OFF
  seed_costs build-asan
  (cd build-asan &&
    ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --output-on-failure -j"$(nproc)" --timeout 900)
fi
