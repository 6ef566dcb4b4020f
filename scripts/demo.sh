#!/usr/bin/env bash
# Sets up (scripts/setup.sh) and runs the demo: the built-in `team` mission (three firefighters, a
# robot, a partial a priori plan) with one pena-entity per member and one pena-fusion on loopback
# Fast DDS, faster than real time (deploy/demo/run-team.sh, docs/demo.md). Writes the global map,
# every trajectory and report.md/report.json under demo-out/ (or the directory given as $1);
# serves the live console (pena-console, printed address) while the team runs and writes
# console.png, its screenshot at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
PENA_TARGETS="pena pena-entity pena-fusion pena-console" bash scripts/setup.sh
build_dir=${PENA_BUILD_DIR:-build}
out=${1:-demo-out}
export FASTRTPS_DEFAULT_PROFILES_FILE="$PWD/deploy/dds/pena-loopback.xml"
PENA_BUILD="$(realpath "$build_dir")" bash deploy/demo/run-team.sh "$out"
