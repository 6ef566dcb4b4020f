#!/usr/bin/env bash
# Sets up (scripts/setup.sh) and runs the demo: simulates the built-in rescue missions and writes
# their logs, ground truth and pictures under demo-out/ (or the directory given as $1).
set -euo pipefail
cd "$(dirname "$0")/.."
PENA_TARGETS=pena bash scripts/setup.sh
build_dir=${PENA_BUILD_DIR:-build}
out=${1:-demo-out}
export FASTRTPS_DEFAULT_PROFILES_FILE="$PWD/deploy/dds/pena-loopback.xml"
pena="$build_dir/tools/pena/pena"
for scenario in loop170 office team; do
  "$pena" simulate --scenario "$scenario" --seed 1 --out "$out/$scenario"
  "$pena" info "$out/$scenario"/*/sensors.penalog
done
echo
echo "demo: missions written to $(realpath "$out"); pictures: $out/*/mission.png"
