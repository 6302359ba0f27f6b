#!/usr/bin/env bash
# Learns the afraid map from many rawlogs in parallel: one .afraid per rawlog
# (risknav-afraid-learn, one GNU parallel job each), then one merge-only run of
# those files into OUTDIR. The merged .afraid equals, byte for byte, the one a
# single run over all the rawlogs writes (each rawlog's replay depends only on
# the rawlog: its filter seed on the config seed and the rawlog's file name and
# size; the counts add up in any order).
#
#   scripts/learn_parallel.sh [-j N] CONFIG.ini OUTDIR RAWLOG...
#
#   -j N            workers (default: $JOBS, else nproc)
#   RISKNAV_LEARN   the risknav-afraid-learn binary (default: build/bin/ of this
#                   checkout, else the one on PATH)
#
# OUTDIR/per-rawlog/<k>-<name>/ holds each rawlog's run (its .afraid is
# rawlog.afraid, its stderr <k>-<name>.log next to it); OUTDIR holds the merged
# results (the config's afraid_name, zones, pictures, summary.json). The
# config's own rawlogs and groundtruth_file are not used; its afraid_in, if
# any, is added once (by the first rawlog's run). A rawlog's ground truth is
# <stem>_groundtruth.txt next to it, or groundtruth.txt next to a
# risknav-simulate simulation.rawlog; none otherwise (it only scores MCL).
# Any failure: exit non-zero with one line on stderr.
set -euo pipefail
me=learn_parallel.sh
die() {
  echo "$me: $*" >&2
  exit 1
}

# ---- one job (run by GNU parallel): worker INDEX RAWLOG
if [ "${1:-}" = "__worker" ]; then
  idx=$2 rawlog=$3
  base=$(basename -- "$rawlog")
  name=$(printf '%03d-%s' "$idx" "${base%.*}")
  dir="$LP_OUT/per-rawlog/$name"
  gt=""
  if [ -f "${rawlog%.*}_groundtruth.txt" ]; then
    gt="${rawlog%.*}_groundtruth.txt"
  elif [ "$base" = "simulation.rawlog" ] && [ -f "$(dirname -- "$rawlog")/groundtruth.txt" ]; then
    gt="$(dirname -- "$rawlog")/groundtruth.txt"
  fi
  args=(-q -o "$dir" --set "AfraidLearn.rawlogs=\"$rawlog\""
    --set "AfraidLearn.groundtruth_file=${gt:+\"$gt\"}"
    --set AfraidLearn.afraid_name=rawlog.afraid)
  # The config's own afraid_in counts once: in the first rawlog's file only.
  [ "$idx" -eq 1 ] || args+=(--set AfraidLearn.afraid_in=)
  log="$LP_OUT/per-rawlog/$name.log"
  rc=0
  "$LP_BIN" "${args[@]}" "$LP_CONFIG" 2>"$log" || rc=$?
  if [ "$rc" -ne 0 ]; then
    echo "$me: $rawlog: $(tail -n 1 "$log") (exit $rc)" >&2
    exit "$rc"
  fi
  if grep -q '"status": "diverged"' "$dir/summary.json" 2>/dev/null; then
    echo "$me: warning: $rawlog: localization diverged (its frames add nothing)" >&2
  fi
  exit 0
fi

# ---- the driver
jobs=${JOBS:-}
while getopts "j:h" opt; do
  case $opt in
    j) jobs=$OPTARG ;;
    h) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "usage: $me [-j N] CONFIG.ini OUTDIR RAWLOG..." ;;
  esac
done
shift $((OPTIND - 1))
[ $# -ge 3 ] || die "usage: $me [-j N] CONFIG.ini OUTDIR RAWLOG..."
[ -n "$jobs" ] || jobs=$(nproc)
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "-j '$jobs': must be a positive integer"

parallel --version 2>/dev/null | grep -q "GNU parallel" ||
  die "GNU parallel not found (Debian package 'parallel'; scripts/setup.sh installs it)"
bin=${RISKNAV_LEARN:-}
if [ -z "$bin" ]; then
  bin="$(cd "$(dirname -- "$0")/.." && pwd)/build/bin/risknav-afraid-learn"
  [ -x "$bin" ] || bin=$(command -v risknav-afraid-learn || true)
fi
if [ -z "$bin" ] || [ ! -x "$bin" ]; then
  die "risknav-afraid-learn not found (build it, or set RISKNAV_LEARN)"
fi

config=$1 out=$2
shift 2
[ -f "$config" ] || die "$config: config not found"
# Absolute paths (the app resolves relative ones against the config's folder);
# symlinks are kept, not resolved: the filter seed depends on the file name.
config=$(realpath -s -- "$config")
out=$(realpath -s -m -- "$out")
case $out in *'"'*) die "$out: a path with a double quote cannot be given to the learner" ;; esac
list=$(mktemp)
trap 'rm -f "$list" "$list.err"' EXIT
merged=""
k=0
for r in "$@"; do
  [ -f "$r" ] || die "$r: rawlog not found"
  r=$(realpath -s -- "$r")
  case $r in *'"'*) die "$r: a path with a double quote cannot be given to the learner" ;; esac
  k=$((k + 1))
  printf '%s\0' "$r" >>"$list"
  b=$(basename -- "$r")
  merged+="${merged:+ }\"$out/per-rawlog/$(printf '%03d-%s' "$k" "${b%.*}")/rawlog.afraid\""
done
mkdir -p -- "$out/per-rawlog" || die "$out: cannot create the output folder"

export LP_OUT="$out" LP_CONFIG="$config" LP_BIN="$bin"
rc=0
parallel --will-cite -0 -a "$list" -j "$jobs" --halt now,fail=1 \
  "$(printf '%q' "$(realpath -- "$0")")" __worker '{#}' '{}' 2>"$list.err" || rc=$?
if [ "$rc" -ne 0 ]; then
  line=$(grep -m 1 "^$me: /" "$list.err" || true)
  echo "${line:-$me: a worker failed (GNU parallel exit $rc): $(tail -n 1 "$list.err")}" >&2
  exit 1
fi
grep "^$me: warning" "$list.err" >&2 || true

# The merge: no rawlog, every per-rawlog .afraid.
"$bin" -o "$out" --set AfraidLearn.rawlogs= --set AfraidLearn.groundtruth_file= \
  --set "AfraidLearn.afraid_in=$merged" "$config"
