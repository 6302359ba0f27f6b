#!/usr/bin/env bash
# Performance figures quoted in docs/PERFORMANCE.md: Google Benchmark of the simulator
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
all_ = json.load(open(sys.argv[1]))["benchmarks"]
b = {x["name"].split("/")[0]: x for x in all_}
fast, brute = b["BM_DmaxFast_1000Poses"]["real_time"], b["BM_DmaxBruteForce_1000Poses"]["real_time"]
print("D_max, 1000 poses, 1000 x 1000 grid, 5 %% obstacles: fast %.3f ms, brute force %.1f ms: %.0fx" % (fast, brute, brute / fast))
for x in all_:
    if x["name"].startswith("BM_Route50m"):
        print("50 m route at 5 cm steps, %s: %.2f ms" % (x.get("label", x["name"]), x["real_time"]))
PY
rm -f "$json"

# Kernel ridge regression at map scale (2000 x 2000 cells).
build/bin/risknav_bench_afraid

# Afraid learner vs MRPT's pf-localization: same rawlog, map, initial box and
# particle settings (5000 initial, KLD as pf-localization's demo), one after
# the other in this run; and peak memory for a 1-lap vs a 10-lap rawlog.
tmp=$(mktemp -d)
cat > "$tmp/pf.ini" <<INI
[KLD_options]
KLD_binSize_PHI=10
KLD_binSize_XY=0.10
KLD_delta=0.01
KLD_epsilon=0.01
KLD_maxSampleSize=40000
KLD_minSampleSize=150
KLD_minSamplesPerBin=0
[PF_options]
PF_algorithm=0
resamplingMethod=0
adaptiveSampleSize=1
BETA=0.5
sampleSize=1
[LocalizationExperiment]
map_file=$PWD/datasets/corridor-doors/corridor.gridmap.gz
rawlog_file=$PWD/datasets/corridor-doors/corridor.rawlog
logOutput_dir=$tmp/pflog
3DSceneFrequency=-1
particles_count=5000
init_PDF_mode=0
init_PDF_min_x=1
init_PDF_max_x=3
init_PDF_min_y=3.5
init_PDF_max_y=5.5
SHOW_PROGRESS_3D_REAL_TIME=false
[MetricMap]
occupancyGrid_count=1
[MetricMap_occupancyGrid_00_creationOpts]
resolution=0.05
[MetricMap_occupancyGrid_00_likelihoodOpts]
likelihoodMethod=4
LF_decimation=5
LF_stdHit=0.20
LF_maxCorrsDistance=0.30
INI
/usr/bin/time -f "%e %M" -o "$tmp/t_pf" pf-localization "$tmp/pf.ini" < /dev/null > /dev/null 2>&1
/usr/bin/time -f "%e %M" -o "$tmp/t_ours" build/bin/risknav-afraid-learn -q -o "$tmp/af" datasets/corridor-doors/afraid.ini
pf=$(tail -1 "$tmp/t_pf"); ours=$(tail -1 "$tmp/t_ours")
python3 -c "
pf, ours = '$pf'.split(), '$ours'.split()
print('corridor rawlog (3959 frames): pf-localization %s s, %d MB; risknav-afraid-learn %s s, %d MB: %.2fx its wall time' % (pf[0], int(pf[1])//1024, ours[0], int(ours[1])//1024, float(ours[0]) / float(pf[0])))"
for laps in 1 10; do
  mkdir -p "$tmp/w$laps"
  cp datasets/corridor-doors/corridor.png "$tmp/w$laps/"
  build/bin/risknav-simulate -q -o "$tmp/w$laps/sim" --set Route.laps=$laps --set Simulation.duration_max=20000 datasets/corridor-doors/world.ini
  /usr/bin/time -f "%e %M" -o "$tmp/t_$laps" build/bin/risknav-afraid-learn -q -o "$tmp/w$laps/af" --set AfraidLearn.rawlogs="$tmp/w$laps/sim/simulation.rawlog" --set AfraidLearn.groundtruth_file="$tmp/w$laps/sim/groundtruth.txt" datasets/corridor-doors/afraid.ini
  r=$(tail -1 "$tmp/t_$laps")
  frames=$(python3 -c "import json; print(json.load(open('$tmp/w$laps/af/summary.json'))['frames'])")
  echo "afraid-learn, $laps lap(s), $frames frames: wall ${r% *} s, peak RSS $(( ${r#* } / 1024 )) MB"
done
rm -rf "$tmp"

# Viewpoint planner (M4): the full sweep (9 safety margins, k = 10 paths each,
# viewpoints planned on all) on bench_viewpoint's generated 20 x 14 m world;
# target <= 500 ms on 2 cores. Medians of 5 runs.
json=$(mktemp)
build/bin/risknav_bench_viewpoint --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_format=json --benchmark_out="$json" --benchmark_out_format=json >/dev/null
python3 - "$json" <<'PY'
import json, os, sys
b = {x["run_name"].split("/")[0]: x for x in json.load(open(sys.argv[1]))["benchmarks"]
     if x.get("aggregate_name") == "median"}
full, one = b["BM_ViewpointFullSweep"], b["BM_ViewpointFullSweep_1Thread"]
print("viewpoint full sweep, 50 obstacles, 30 landmarks: %.0f ms (%d threads), %.0f ms (1 thread)"
      % (full["real_time"], os.cpu_count(), one["real_time"]))
print("  %d of %d (S, path) plans feasible, at %d of 9 S; optimal plan: %s; visibility graph %d nodes at S = 20 mm"
      % (full["feasible_plans"], full["total_paths"], full["S_with_feasible"],
         "yes" if full["optimal"] else "none", full["graph_nodes_first_S"]))
PY
rm -f "$json"

# One navigation step: CRiskAwareReactiveNav with all three
# limiters vs a bare CReactiveNavigationSystem on the same office world and
# config, side by side in one run; and each limiter's limit() call alone.
build/bin/risknav_bench_nav --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  | grep -E "median|Benchmark"
