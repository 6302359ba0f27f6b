#!/usr/bin/env bash
# Regenerates the committed dataset files from the bundled worlds:
#   datasets/corridor-doors/corridor.rawlog, corridor_groundtruth.txt, corridor.gridmap.gz
# Run after changing the maps (scripts/make_maps.py) or the simulator.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
tmp=$(mktemp -d)
build/bin/risknav-simulate -q -o "$tmp" datasets/corridor-doors/world.ini
cp "$tmp/simulation.rawlog" datasets/corridor-doors/corridor.rawlog
cp "$tmp/groundtruth.txt" datasets/corridor-doors/corridor_groundtruth.txt
cp "$tmp/map.gridmap.gz" datasets/corridor-doors/corridor.gridmap.gz
rm -rf "$tmp"
ls -la datasets/corridor-doors/
