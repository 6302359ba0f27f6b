#!/usr/bin/env bash
# Performance figures quoted in README.md: Google Benchmark of the simulator
# engine, then whole-process wall time and peak memory of risknav-simulate for
# 1, 3 and 10 laps of the corridor world (peak memory must not grow: the
# rawlog is streamed to disk).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
build/bin/risknav_bench_simulate --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
tmp=$(mktemp -d)
for laps in 1 3 10; do
  /usr/bin/time -f "risknav-simulate corridor, $laps lap(s): wall %e s, peak RSS %M KB" \
    build/bin/risknav-simulate -q --set Route.laps=$laps --set Simulation.duration_max=20000 \
    -o "$tmp/run" datasets/corridor-doors/world.ini
  python3 -c "import json,sys; j=json.load(open('$tmp/run/summary.json')); print('  simulated %.0f s, %d frames, %.0fx real time' % (j['duration_s'], j['frames'], j['timing']['realtime_factor']))"
done
rm -rf "$tmp"
