#!/usr/bin/env bash
# Configures and builds risknav (Release, tests and benchmarks) into build/.
# Extra arguments are passed to CMake's configure step, e.g.
#   BUILD_DIR=build-asan scripts/build.sh -DRISKNAV_SANITIZE=ON
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# the progress lines filtered out; a failed build fails the script (grep's
# status, 1 when it filtered everything, is not the build's)
set +e
cmake --build "$BUILD_DIR" -j"$(nproc)" -- --no-print-directory 2>&1 |
  grep -v -E "^\[ *[0-9]+%\] (Building|Linking|Built)"
status=${PIPESTATUS[0]}
set -e
if [ "$status" -ne 0 ]; then
  echo "build.sh: the build in $BUILD_DIR failed (exit $status)" >&2
  exit "$status"
fi
test -x "$BUILD_DIR/bin/risknav-simulate"
