#!/usr/bin/env bash
# The demo on a fresh Debian 12 machine: installs what is missing, builds, and
# runs the apps on the bundled datasets. Results go to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BIN=build/bin
OUT=out/demo
mkdir -p "$OUT"

for world in corridor-doors office; do
  "$BIN/risknav-simulate" "datasets/$world/world.ini" --out "$OUT/simulate-$world"
done

echo
echo "demo results in $OUT/:"
for world in corridor-doors office; do
  echo "  $OUT/simulate-$world/world.png           picture of the run"
  echo "  $OUT/simulate-$world/simulation.rawlog   MRPT rawlog (rawlog-edit --info -i ...)"
  echo "  $OUT/simulate-$world/summary.json        figures"
done
