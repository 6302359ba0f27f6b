#!/usr/bin/env bash
# Proves a refactor behaviour-preserving: runs every app on the bundled configs
# it accepts (fixed seeds), then compares two such output trees.
#
#   scripts/compare_outputs.sh BIN_DIR OUT_DIR     run the apps into OUT_DIR/<app>-<config>
#   scripts/compare_outputs.sh --diff DIR_A DIR_B  compare two trees file by file
#
# ONLY=REGEX limits the runs to the output names matching it (e.g. ONLY=navigate).
# --diff compares byte for byte, except timing figures that differ run to run:
# summary.json keys and CSV columns whose names speak of ms, wall, cpu, seconds
# of compute or time of day are left out, and PNGs are compared by pixels
# (ImageMagick `compare -metric AE`), MRPT's .reactivenavlog (wall-clock
# timings in every record) by its unpacked length; the output folder's own
# path is ignored. It prints one line per differing file and
# exits 1 if there is any, 0 if the trees are the same.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"

usage() {
  sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}

if [[ "${1:-}" == "--diff" ]]; then
  [[ $# -eq 3 && -d "$2" && -d "$3" ]] || usage
  exec python3 - "$2" "$3" <<'EOF'
import csv, gzip, io, json, os, re, subprocess, sys

a_root, b_root = sys.argv[1], sys.argv[2]
# names of timing figures: *_ms, ms_*, wall*, cpu*, time of day, compute seconds
# (summary.json's "timing" object holds them all: wall_time_s, steps_per_s, ...)
TIMING = re.compile(r"(^|[_\s.-])(ms|wall|cpu|elapsed|timestamp|date|"
                    r"time_of_day|started|finished)([_\s.-]|$)|wall|cpu_|_ms$|"
                    r"^ms_|^timing$|per_s$|realtime|seconds_compute|compute_s", re.I)

def files(root):
    out = set()
    for d, _, fs in os.walk(root):
        for f in fs:
            out.add(os.path.relpath(os.path.join(d, f), root))
    return out

def strip_json(v):
    if isinstance(v, dict):
        return {k: strip_json(x) for k, x in v.items() if not TIMING.search(k)}
    if isinstance(v, list):
        return [strip_json(x) for x in v]
    return v

def same_json(a, b):
    try:
        return strip_json(json.loads(a)) == strip_json(json.loads(b))
    except ValueError:
        return False

def csv_rows(data):
    rows = list(csv.reader(io.StringIO(data.decode("utf-8", "replace"))))
    if not rows:
        return rows
    keep = [i for i, h in enumerate(rows[0]) if not TIMING.search(h.strip())]
    return [[r[i] for i in keep if i < len(r)] for r in rows]

def same_png(pa, pb):
    try:
        p = subprocess.run(["compare", "-metric", "AE", pa, pb, "null:"],
                           capture_output=True, text=True)
    except FileNotFoundError:
        return False
    return p.returncode == 0 and p.stderr.strip().split(" ")[0] in ("0", "0.0")

def navlog_size(data):
    try:
        return len(gzip.decompress(data))
    except OSError:
        return len(data)

fa, fb = files(a_root), files(b_root)
bad = 0
for rel in sorted(fa | fb):
    if rel not in fb:
        print("only in %s: %s" % (a_root, rel)); bad += 1; continue
    if rel not in fa:
        print("only in %s: %s" % (b_root, rel)); bad += 1; continue
    pa, pb = os.path.join(a_root, rel), os.path.join(b_root, rel)
    with open(pa, "rb") as f: da = f.read()
    with open(pb, "rb") as f: db = f.read()
    if da == db:
        continue
    # the output folder's own path (e.g. a route file made by an earlier run)
    da = da.replace(os.path.abspath(a_root).encode(), b"@OUT@")
    db = db.replace(os.path.abspath(b_root).encode(), b"@OUT@")
    if da == db:
        continue
    name = os.path.basename(rel)
    if name.endswith(".json") and same_json(da, db):
        continue
    if name.endswith(".csv") and csv_rows(da) == csv_rows(db):
        continue
    if name.endswith(".png") and same_png(pa, pb):
        continue
    # MRPT's navlog stores each cycle's wall-clock timings (two runs of one
    # binary differ): the same records, so the same length unpacked
    if name.endswith(".reactivenavlog") and navlog_size(da) == navlog_size(db):
        continue
    print("differs: %s" % rel); bad += 1
print("compared %d files: %s" % (len(fa | fb),
      "identical" if bad == 0 else "%d differ" % bad))
sys.exit(1 if bad else 0)
EOF
fi

[[ $# -eq 2 && -d "$1" ]] || usage
BIN="$(cd "$1" && pwd)"
OUT="$2"
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"
cd "$ROOT"

# app  config  [extra arguments]; the output goes to OUT/<app>-<dir>-<config>
RUNS=(
  "simulate corridor-doors/world.ini"
  "simulate office/world.ini"
  "simulate validation/t_junction.ini"
  "risk-eval risk-two-routes/risk.ini"
  "afraid-learn corridor-doors/afraid.ini"
  "explore office/explore.ini"
  "explore validation/explore_t_junction.ini"
  "viewpoint-plan landmarks-two-routes/r1.ini"
  "viewpoint-plan landmarks-two-routes/r2.ini"
  "viewpoint-plan landmarks-corridor/r1.ini"
  "viewpoint-plan landmarks-corridor/r2.ini"
  "viewpoint-plan landmarks-pillars/r1.ini"
  "viewpoint-plan landmarks-pillars/r2.ini"
  "viewpoint-plan office/viewpoint.ini"
  "navigate office/navigate.ini"
  "navigate office/navigate_m1.ini"
  "navigate office/navigate_m4.ini --set Navigate.route_file=@OUT@/viewpoint-plan-office-viewpoint/waypoints.ini"
  "navigate risk-two-routes/navigate.ini"
  "navigate corridor-doors/afraid_experiment.ini --set AfraidExperiment.seeds=1"
)

status=0
for run in "${RUNS[@]}"; do
  read -r app config extra <<<"$run"
  name="$app-$(dirname "$config")-$(basename "$config" .ini)"
  [[ -z "${ONLY:-}" || "$name" =~ $ONLY ]] || continue
  extra="${extra//@OUT@/$OUT}"
  rm -rf "${OUT:?}/$name"
  t0=$(date +%s)
  # shellcheck disable=SC2086
  if "$BIN/risknav-$app" "datasets/$config" -q --out "$OUT/$name" $extra \
    >"$OUT/$name.stdout" 2>"$OUT/$name.stderr"; then
    rc=0
  else
    rc=$?
    status=1
  fi
  echo "$name: exit $rc, $(($(date +%s) - t0)) s"
done
exit $status
