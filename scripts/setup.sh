#!/usr/bin/env bash
# Installs the Debian packages risknav needs, only those that are missing.
# Idempotent; prints nothing when everything is already there. Uses sudo when
# not run as root.
set -euo pipefail

PACKAGES=(
  g++ cmake make pkg-config python3
  libmrpt-dev mrpt-apps mrpt-common      # MRPT 2.5: libraries, apps (rawlog-edit, pf-localization), datasets
  libopencv-dev nlohmann-json3-dev       # images, summary.json
  libyaml-dev                            # ROS map YAML files (a real YAML parser)
  libgtest-dev libbenchmark-dev          # tests, benchmarks
  xvfb xauth imagemagick time x11-utils xdotool  # headless runs of MRPT's GUI apps (navlog-viewer), screenshots, peak memory
  parallel                               # scripts/learn_parallel.sh (GNU parallel)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done" >&2
