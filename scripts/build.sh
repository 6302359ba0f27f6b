#!/usr/bin/env bash
# Configures and builds risknav (Release, tests and benchmarks) into build/.
# Extra arguments are passed to CMake's configure step, e.g.
#   BUILD_DIR=build-asan scripts/build.sh -DRISKNAV_SANITIZE=ON
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" -- --no-print-directory 2>&1 | grep -v -E "^\[ *[0-9]+%\] (Building|Linking|Built)" || true
test -x "$BUILD_DIR/bin/risknav-simulate"
