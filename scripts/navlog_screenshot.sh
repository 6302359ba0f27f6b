#!/usr/bin/env bash
# Screenshot of MRPT's navlog-viewer showing a navlog, under a virtual X server.
#
#   scripts/navlog_screenshot.sh NAVLOG OUT.png [RECORD]
#
# Starts navlog-viewer on NAVLOG (a .reactivenavlog, e.g. risknav-navigate's
# navigation.reactivenavlog) inside `xvfb-run`, waits until its window is up,
# the file has been read (the viewer holds it open while loading) and the
# first frame is drawn (the viewer builds the PTGs' collision grids before
# that: seconds), checks that the viewer is still running, and saves the whole
# screen with ImageMagick's `import -window root`.
# With xdotool installed it also fits the window to the screen (Xvfb has no
# window manager to maximize it), moves the per-PTG "TP-Obstacles" panels to
# the top right so that they do not hide the text overlay, and, given RECORD
# (a record index), ticks "Show all debug fields" (the record's values and
# additional_debug_msgs, e.g. risknav's speed_limiter, are printed over the
# view) and steps the time slider to RECORD with the Right arrow key. Without
# xdotool the initial view (record 0) is shot and a note on stderr says so.
#
# Prints one line: "navlog-viewer: window after A s, log loaded after B s,
# drawn after C s, record R; screenshot OUT.png".
# Exit status: 0 done; 1 the viewer exited, or did not show/load/draw in time
# (its output is printed); 2 usage; 3 a tool is missing.
# Environment: NAVLOG_WAIT_S (seconds allowed for start-up, default 30),
# NAVLOG_SCREEN (Xvfb screen, default 1600x1000x24), NAVLOG_PAN ("DX DY":
# with xdotool, pan the scene by right-dragging it that many pixels, e.g. to
# bring the robot out from under the text; the camera only follows the robot
# when it is far from the view's centre).
#
# docs/images/navlog-viewer-office.png was made with (record 190: the robot
# turning into the far room, slowed by CStoppingDistanceLimiter):
#   build/bin/risknav-navigate -o /tmp/navout datasets/office/navigate.ini
#   NAVLOG_PAN="-250 -60" scripts/navlog_screenshot.sh \
#       /tmp/navout/navigation.reactivenavlog docs/images/navlog-viewer-office.png 190
# Debian packages: xvfb xauth mrpt-apps imagemagick x11-utils, optional xdotool.
set -euo pipefail

# Inside the virtual display (this script again, run by xvfb-run, see below).
inner() {
    local navlog=$1 out=$2 record=$3 wait_s=$4 pan=$5
    local log t0 pid tw="" tl="" td="" shot
    log=$(mktemp)
    shot=$(mktemp --suffix=.png)
    t0=$(date +%s%N)
    navlog-viewer "$navlog" >"$log" 2>&1 &
    pid=$!
    stop() {
        kill "$pid" 2>/dev/null || true
        wait "$pid" 2>/dev/null || true
        rm -f "$log" "$shot"
    }
    fail() {
        echo "navlog-viewer: $1" >&2
        sed 's/^/  | /' "$log" >&2
        stop
        exit 1
    }
    alive() { kill -0 "$pid" 2>/dev/null || fail "exited $1"; }
    is_open() { # the viewer holds the navlog open while it reads it
        local fd
        for fd in /proc/"$pid"/fd/*; do
            [ "$(readlink "$fd" 2>/dev/null)" = "$navlog" ] && return 0
        done
        return 1
    }
    elapsed() { awk -v d=$(($(date +%s%N) - t0)) 'BEGIN { printf "%.1f", d / 1e9 }'; }
    grab() { import -window root "$shot" 2>/dev/null; }
    # Pixel signature and standard deviation of the last grab.
    sig() { identify -format '%# %[fx:standard_deviation]' "$shot"; }
    pixel() { identify -format "%[pixel:p{$1,$2}]" "$shot"; }
    # Grabs until two in a row are the same picture (nothing more is drawn).
    settle() {
        local prev="" cur i
        for ((i = 0; i < 40; i++)); do
            sleep 0.5
            alive "$1"
            grab
            cur=$(sig)
            [ "$cur" = "$prev" ] && return 0
            prev=$cur
        done
    }
    local xdo=""
    command -v xdotool >/dev/null && xdo=1
    local screen_w screen_h
    read -r screen_w screen_h < <(xwininfo -root | awk '/Width:/ {w = $2} /Height:/ {h = $2} END {print w, h}')

    # 1. Window mapped, 2. file read (seen open and closed again; a small file
    # may be read between two polls: then never seen open for 3 s), 3. a
    # frame drawn (the screen is no longer uniform).
    local deadline=$(($(date +%s) + wait_s)) seen_open="" win_at=0
    while [ -z "$td" ]; do
        [ "$(date +%s)" -lt "$deadline" ] ||
            fail "not ready after ${wait_s} s (window: ${tw:-no}, loaded: ${tl:-no})"
        alive "during start-up"
        if [ -z "$tw" ] && [[ "$(xwininfo -root -tree 2>/dev/null)" == *'"navlog-viewer"'* ]]; then
            tw=$(elapsed)
            win_at=$(date +%s)
            # Fill the screen (as "maximized" does with a window manager).
            [ -n "$xdo" ] && xdotool search --name '^navlog-viewer$' \
                windowmove 0 0 windowsize "$screen_w" "$screen_h" >/dev/null 2>&1
        fi
        if [ -z "$tl" ]; then
            if is_open; then
                seen_open=1
            elif [ -n "$tw" ] && { [ -n "$seen_open" ] || [ $(($(date +%s) - win_at)) -ge 3 ]; }; then
                tl=$(elapsed)
            fi
        elif grab && [ "$(sig | cut -d' ' -f2)" != 0 ]; then
            td=$(elapsed)
        fi
        sleep 0.1
    done
    settle "while drawing the first record"

    local shown=0
    if [ -n "$xdo" ]; then
        drag() { # from x,y to x,y, by the mouse (a nanogui title bar)
            xdotool mousemove "$1" "$2" mousedown 1
            sleep 0.2
            xdotool mousemove $((($1 + $3) / 2)) $((($2 + $4) / 2))
            sleep 0.2
            xdotool mousemove "$3" "$4"
            sleep 0.2
            xdotool mouseup 1
            sleep 0.3
        }
        # The viewer puts panel n (270x270 + title) at (5 + 270 (n%3),
        # 315 + 270 (n/3)); a title bar is flat grey (a missing panel is the
        # scene: dragging that would turn the camera). Move them, last first,
        # to a 2-column grid in the top right corner.
        local n x y gx=$((screen_w - 545)) title
        for n in 5 4 3 2 1 0; do
            x=$((5 + 270 * (n % 3) + 30))
            y=$((315 + 270 * (n / 3) + 13))
            title=1
            for dx in 0 10 20; do
                [[ "$(pixel $((x + dx)) "$y")" =~ ^srgba?\(([4-7][0-9]),([4-7][0-9]),([4-7][0-9]) ]] &&
                    [ "${BASH_REMATCH[1]}" = "${BASH_REMATCH[2]}" ] || title=""
            done
            [ -n "$title" ] || continue
            drag "$x" "$y" $((gx + 275 * (n % 2) + 30)) $((10 + 300 * (n / 2) + 13))
        done
        if [ -n "$record" ]; then
            # "Control" panel: tab "View options", tick "Show all debug
            # fields", back to tab "Information".
            xdotool mousemove 199 148 click 1
            sleep 0.5
            xdotool mousemove 56 217 click 1
            sleep 0.5
            xdotool mousemove 100 148 click 1
            sleep 0.5
            # Keys go to the window under the pointer (no window manager).
            xdotool mousemove $((screen_w / 2)) $((screen_h / 2))
            if [ "$record" -gt 0 ]; then
                xdotool key --delay 20 --repeat "$record" Right
            fi
            shown=$record
        fi
        if [ -n "$pan" ]; then
            # Right-drag on the scene, from the middle of the screen.
            local cx=$((screen_w / 2)) cy=$((screen_h / 2)) px py
            read -r px py <<<"$pan"
            xdotool mousemove "$cx" "$cy" mousedown 3
            sleep 0.2
            xdotool mousemove $((cx + px / 2)) $((cy + py / 2))
            sleep 0.2
            xdotool mousemove $((cx + px)) $((cy + py))
            sleep 0.2
            xdotool mouseup 3
        fi
        settle "while stepping to record $record"
    elif [ -n "$record" ] && [ "$record" != 0 ]; then
        echo "navlog-viewer: xdotool is not installed: the initial view (record 0) is shot" >&2
    fi
    alive "before the screenshot"
    import -window root "$out"
    alive "while the screenshot was taken"
    stop
    echo "navlog-viewer: window after $tw s, log loaded after $tl s, drawn after $td s," \
        "record $shown; screenshot $out"
}

if [ "${1:-}" = "--inside-xvfb" ]; then
    shift
    inner "$@"
    exit 0
fi

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
    echo "usage: $0 NAVLOG OUT.png [RECORD]" >&2
    exit 2
fi
[ -f "$1" ] || { echo "$0: no such file: $1" >&2; exit 2; }
[ -d "$(dirname "$2")" ] || { echo "$0: no such folder: $(dirname "$2")" >&2; exit 2; }
navlog=$(readlink -f "$1")
out=$(readlink -f "$(dirname "$2")")/$(basename "$2")
record=${3:-}
if [ -n "${NAVLOG_PAN:-}" ] && ! [[ "$NAVLOG_PAN" =~ ^-?[0-9]+\ -?[0-9]+$ ]]; then
    echo "$0: NAVLOG_PAN must be \"DX DY\" (pixels), got '$NAVLOG_PAN'" >&2
    exit 2
fi
if [ -n "$record" ] && ! [[ "$record" =~ ^[0-9]+$ ]]; then
    echo "$0: RECORD must be a record index, got '$record'" >&2
    exit 2
fi
for t in xvfb-run xauth navlog-viewer import identify xwininfo; do
    command -v "$t" >/dev/null || { echo "$0: $t is not installed" >&2; exit 3; }
done

exec xvfb-run -a -s "-screen 0 ${NAVLOG_SCREEN:-1600x1000x24}" \
    bash "$(readlink -f "$0")" --inside-xvfb "$navlog" "$out" "$record" "${NAVLOG_WAIT_S:-30}" \
    "${NAVLOG_PAN:-}"
