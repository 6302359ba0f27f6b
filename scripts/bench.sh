#!/usr/bin/env bash
# Performance figures quoted in README.md: Google Benchmark of the simulator
# and of the risk evaluator
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

# Risk evaluator: D_max fast vs brute force in the same run, and a 50 m route.
json=$(mktemp)
build/bin/risknav_bench_risk --benchmark_format=json --benchmark_out="$json" --benchmark_out_format=json >/dev/null
python3 - "$json" <<'PY'
import json, sys
b = {x["name"].split("/")[0]: x for x in json.load(open(sys.argv[1]))["benchmarks"]}
fast, brute = b["BM_DmaxFast_1000Poses"]["real_time"], b["BM_DmaxBruteForce_1000Poses"]["real_time"]
print("D_max, 1000 poses, 1000 x 1000 grid, 5 %% obstacles: fast %.3f ms, brute force %.1f ms: %.0fx" % (fast, brute, brute / fast))
print("50 m route at 5 cm steps: %.2f ms" % b["BM_Route50m"]["real_time"])
PY
rm -f "$json"
