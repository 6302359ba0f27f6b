#!/usr/bin/env bash
# Runs the libFuzzer targets of tests/fuzz for a bounded time each:
#   scripts/fuzz.sh [SECONDS] [TARGET...]     (default 60 s, all ten targets)
# Installs clang if missing, builds into build-fuzz (clang, ASan+UBSan,
# -DRISKNAV_BUILD_FUZZERS=ON; the normal build/ is not touched), seeds the
# corpora from config/ and datasets/, runs each target in libFuzzer's fork
# mode (a crash is recorded and fuzzing goes on) and prints per target the
# executions, the final coverage (cov: edges, ft: features) and the crashes.
# Crash inputs are copied to tests/fuzz/crashes/<target>/; logs are in
# build-fuzz/fuzz/logs/. Reproduce one: build-fuzz/bin/fuzz_map FILE
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(fuzz_config fuzz_rawlog fuzz_map fuzz_afraid fuzz_world fuzz_waypoints fuzz_ground_truth
                                   fuzz_simplemap fuzz_image fuzz_ros_yaml)
BUILD_DIR=${BUILD_DIR:-build-fuzz}
W=$BUILD_DIR/fuzz

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
    echo "fuzz.sh: installing clang (libFuzzer runtime)"
    apt-get install -y clang >/dev/null
fi

CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DRISKNAV_BUILD_FUZZERS=ON -DRISKNAV_BUILD_TESTS=OFF -DRISKNAV_BUILD_BENCHMARKS=OFF \
    -DRISKNAV_SANITIZE=ON >/dev/null
# only the targets asked for (and the seed maker, which links the afraid
# library, when the map or .afraid corpora need it)
BUILD_TARGETS=("${TARGETS[@]}")
[[ " ${TARGETS[*]} " =~ " fuzz_map " || " ${TARGETS[*]} " =~ " fuzz_afraid " ]] && BUILD_TARGETS+=(fuzz_make_seeds)
cmake --build "$BUILD_DIR" --target "${BUILD_TARGETS[@]}" -j"$(nproc)" -- --no-print-directory 2>&1 \
    | grep -v -E "^\[ *[0-9]+%\] (Building|Linking|Built)" || true
BIN=$BUILD_DIR/bin

# ---- seed corpora (rebuilt every run; the fuzzers add what they find) ----
S=$W/seeds
rm -rf "$S"
mkdir -p "$S"/{fuzz_config,fuzz_rawlog,fuzz_map,fuzz_afraid,fuzz_world,fuzz_waypoints,fuzz_ground_truth,fuzz_simplemap,fuzz_image,fuzz_ros_yaml} "$W"/logs "$W"/helper
# the committed seeds (tests/fuzz/seeds, also replayed by ctest)
for d in tests/fuzz/seeds/*/; do
    cp "$d"* "$S/$(basename "$d")/"
done
for f in config/*.ini datasets/*/*.ini; do
    cp "$f" "$S/fuzz_config/$(echo "$f" | tr / _)"
done
# rawlog: the corridor log's head, plain (readable by the mutator) and gz.
zcat datasets/corridor-doors/corridor.rawlog | head -c 200000 >"$S/fuzz_rawlog/corridor-head.rawlog" || true
zcat datasets/corridor-doors/corridor.rawlog | head -c 20000 | gzip -1 >"$S/fuzz_rawlog/corridor-head-20k.rawlog.gz" || true
zcat datasets/corridor-doors/corridor.rawlog | head -c 4000 >"$S/fuzz_rawlog/corridor-head-4k.rawlog" || true
# map: first byte = format (0 bitmap, 1 .gridmap, 2 .gridmap.gz, 3 ROS yaml; see fuzz_map.cpp)
[ -x "$BIN/fuzz_make_seeds" ] && "$BIN/fuzz_make_seeds" datasets/validation/narrow_doors.png "$W/helper"
for f in datasets/*/*.png; do
    { printf '\x00'; cat "$f"; } >"$S/fuzz_map/png-$(basename "$f")"
done
{ printf '\x01'; zcat datasets/corridor-doors/corridor.gridmap.gz; } >"$S/fuzz_map/gridmap-corridor"
if [ -f "$W/helper/small.gridmap.gz" ]; then
    { printf '\x01'; zcat "$W/helper/small.gridmap.gz"; } >"$S/fuzz_map/gridmap-small"
    { printf '\x02'; cat "$W/helper/small.gridmap.gz"; } >"$S/fuzz_map/gridmapgz-small"
fi
{ printf '\x03'; printf 'image: map.png\nresolution: 0.05\norigin: [-1.0, 2.5, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n'; } >"$S/fuzz_map/yaml-trinary"
{ printf '\x03'; printf 'image: map.png\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 1\nmode: scale\n'; } >"$S/fuzz_map/yaml-scale"
# simplemap: MRPT's demo maps, decompressed (the committed seed is small)
for f in /usr/share/mrpt/datasets/*.simplemap.gz; do
    [ -f "$f" ] && zcat "$f" >"$S/fuzz_simplemap/$(basename "$f" .gz)"
done
# images: every dataset bitmap (PNG) besides the small PNG/JPEG/TIFF/BMP/PNM seeds
for f in datasets/*/*.png; do
    cp "$f" "$S/fuzz_image/$(echo "$f" | tr / _)"
done
# .afraid: uncompressed content (what decode() reads) made by the helper.
cp "$W"/helper/small-*.afraid "$S/fuzz_afraid/" 2>/dev/null || true
# polygon worlds (viewpoint planner): every dataset's world.txt
# (landmarks-two-routes, ...), and a small one with a hole, a landmark radius
# and a trailing comment (lines the datasets may have none of).
for f in datasets/*/world.txt; do
    cp "$f" "$S/fuzz_world/$(echo "$f" | tr / _)"
done
printf '# hole\nbounds -1 -1 6 5\nobstacle 0 0 4 0 4 3 0 3\nhole 1 1 1 2 3 2 3 1\nlandmark A 2 1 90 0.1\nlandmark B 0 1.5 180 # outer face\n' \
    >"$S/fuzz_world/hole.txt"
# waypoint files (risknav-navigate route_file): a small MRPT TWaypointSequence
# with a [Viewpoints] tag (and whatever waypoints.ini a run left in out/).
printf '[Waypoints]\nwaypoint_count = 2\nwp000_target_x = 1\nwp000_target_y = 2\nwp000_allowed_distance = 0.05\nwp000_allow_skip = true\nwp001_target_x = 3.5\nwp001_target_y = -1e-3\nwp001_allow_skip = false\nwp001_speed_ratio = 1\nwp001_target_frame_id = map\n[Viewpoints]\nwaypoint_1 = B L1+L2 pan_left_deg=10 pan_right_deg=-5\n' \
    >"$S/fuzz_waypoints/two.ini"
for f in out/*/waypoints.ini; do
    [ -f "$f" ] && cp "$f" "$S/fuzz_waypoints/$(echo "$f" | tr / _)"
done

# ground truth (risknav-afraid-learn groundtruth_file): "t x y phi" lines as
# risknav-simulate writes them, with a comment, a blank line and CRLF.
printf '%% t x y phi\n0 1.5 2.25 0\n0.2 1.6 2.25 -0.01\n\n# pause\n0.4 1.7e0 2.3 3.14159\r\n' \
    >"$S/fuzz_ground_truth/small.txt"
for f in datasets/*/*groundtruth*.txt; do
    [ -f "$f" ] && head -c 16000 "$f" >"$S/fuzz_ground_truth/$(echo "$f" | tr / _)"
done

max_len() {
    case $1 in
        fuzz_config) echo 16384 ;;
        fuzz_rawlog) echo 204800 ;;
        fuzz_map) echo 125000 ;;
        fuzz_afraid) echo 32768 ;;
        fuzz_world) echo 16384 ;;
        fuzz_waypoints) echo 16384 ;;
        fuzz_ground_truth) echo 16384 ;;
        fuzz_simplemap) echo 204800 ;;
        fuzz_image) echo 131072 ;;
        fuzz_ros_yaml) echo 16384 ;;
    esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
SUMMARY=$W/summary.txt
printf '%-12s %10s %7s %7s %7s  %s\n' target executions cov ft crashes "(${SECONDS_PER_TARGET} s each)" >"$SUMMARY"
for t in "${TARGETS[@]}"; do
    C=$W/corpus/$t
    A=$W/artifacts/$t
    rm -rf "$A"  # the artifacts of this run only
    mkdir -p "$C" "$A"
    cp -n "$S/$t"/* "$C/" 2>/dev/null || true
    LOG=$W/logs/$t.log
    echo "== $t: ${SECONDS_PER_TARGET} s, corpus $(ls "$C" | wc -l) files"
    # Fork mode: a crash / OOM / timeout is saved and fuzzing continues.
    "$BIN/$t" "$C" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
        -max_total_time="$SECONDS_PER_TARGET" -max_len="$(max_len "$t")" \
        -timeout=20 -rss_limit_mb=2560 -malloc_limit_mb=2048 \
        -artifact_prefix="$A/" >"$LOG" 2>&1 || true
    last=$(grep -E '^#[0-9]+.*cov: ' "$LOG" | tail -1 || true)
    execs=$(sed -nE 's/^#([0-9]+).*/\1/p' <<<"$last")
    cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
    ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
    n=$(find "$A" -type f ! -name '*.log' | wc -l)
    printf '%-12s %10s %7s %7s %7s\n' "$t" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$n" >>"$SUMMARY"
    if [ "$n" -gt 0 ]; then
        mkdir -p "tests/fuzz/crashes/$t"
        find "$A" -type f ! -name '*.log' -exec cp {} "tests/fuzz/crashes/$t/" \;
        # Fork mode keeps the inner logs short: re-run (up to 5) inputs for the cause.
        for a in $(find "$A" -type f ! -name '*.log' | head -5); do
            timeout 300 "$BIN/$t" -rss_limit_mb=2560 -malloc_limit_mb=2048 "$a" >"$a.log" 2>&1 || true
            why=$( (grep -hE 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|SUMMARY: |what\(\)' "$a.log" || true) | head -3 | cut -c1-200)
            # The first frame past the sanitizer / libFuzzer / allocator ones, and
            # the first frame in risknav's own code.
            frames=$( (grep -hE '^ +#[0-9]+ ' "$a.log" || true) | sed -E 's/^ +#[0-9]+ 0x[0-9a-f]+ (in )?//; s/ \(BuildId.*//')
            at=$( (grep -vE '__sanitizer|__asan|__ubsan|fuzzer::|operator new|libstdc\+\+|^\(' <<<"$frames" || true) | head -1 | cut -c1-160)
            own=$( (grep -F -e "$PWD/libs/" -e "$PWD/tests/" <<<"$frames" || true) | grep -v LLVMFuzzerTestOneInput | head -1 | cut -c1-160)
            { echo "    $(basename "$a"):"; sed 's/^/      /' <<<"$why"
              [ -z "$at" ] || echo "      at $at"; [ -z "$own" ] || [ "$own" = "$at" ] || echo "      from $own"; } >>"$SUMMARY"
        done
    fi
done
# Temporary inputs of fuzzer processes that have ended (/tmp/risknav-fuzz-PID-*).
for f in /tmp/risknav-fuzz-*; do
    [ -e "$f" ] || continue
    pid=${f#/tmp/risknav-fuzz-}; pid=${pid%%-*}
    kill -0 "$pid" 2>/dev/null || rm -rf "$f"
done
echo
cat "$SUMMARY"
