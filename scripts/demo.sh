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

"$BIN/risknav-risk-eval" datasets/risk-two-routes/risk.ini --out "$OUT/risk-eval"
"$BIN/risknav-afraid-learn" datasets/corridor-doors/afraid.ini --out "$OUT/afraid-learn"
"$BIN/risknav-explore" datasets/office/explore.ini --out "$OUT/explore"
for robot in r1 r2; do
  "$BIN/risknav-viewpoint-plan" "datasets/landmarks-two-routes/$robot.ini" --out "$OUT/viewpoint-$robot"
done
"$BIN/risknav-navigate" datasets/office/navigate.ini --out "$OUT/navigate-office"
"$BIN/risknav-navigate" datasets/corridor-doors/afraid_experiment.ini --set AfraidExperiment.seeds=1 \
  --out "$OUT/navigate-afraid-experiment"

echo
echo "demo results in $OUT/:"
for world in corridor-doors office; do
  echo "  $OUT/simulate-$world/world.png           picture of the run"
  echo "  $OUT/simulate-$world/simulation.rawlog   MRPT rawlog (rawlog-edit --info -i ...)"
  echo "  $OUT/simulate-$world/summary.json        figures"
done
echo "  $OUT/risk-eval/paths.png            candidate routes, the best highlighted"
echo "  $OUT/risk-eval/ellipses_A.png       standard and maximum error ellipses along route A"
echo "  $OUT/risk-eval/risk_profile.png     u = 1/D_max^2 along every route"
echo "  $OUT/risk-eval/risk_table.csv       U for every route x sensing subset"
echo "  $OUT/afraid-learn/afraid.png        the learned afraid level, events and zones on the map"
echo "  $OUT/afraid-learn/profile.png       events and level along the corridor (cf. the paper's Figs. 8-9)"
echo "  $OUT/afraid-learn/speed.png         the resulting speed limit along the corridor"
echo "  $OUT/afraid-learn/speed_mask.yaml   Nav2 Speed Filter mask of the zones"
echo "  $OUT/explore/trace.png              adaptive vs fixed speeds through the unknown office"
echo "  $OUT/explore/speed_profile.png      speed vs distance, coloured by what limited it"
echo "  $OUT/explore/snapshots/             the free-space map and the plans where the speed changes"
echo "  $OUT/viewpoint-r1/plan.png          robot R1's optimal path, viewpoints and strategies (short route)"
echo "  $OUT/viewpoint-r2/plan.png          robot R2's (long route); sweep.md: the paper's Tables II/III"
echo "  $OUT/navigate-office/trajectory.png  MRPT's reactive engine with the limiters, closed loop (speed colours)"
echo "  $OUT/navigate-office/navigation.reactivenavlog  for MRPT's navlog-viewer"
echo "  $OUT/navigate-afraid-experiment/experiment.md   learned afraid limiter vs v_safe vs v_max (seed 1)"
