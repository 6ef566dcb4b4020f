#!/usr/bin/env bash
# How old a pose is when the console's page gets it: pena-load publishes N entities at 4 Hz
# (replayed from the team mission) against pena-fusion, pena-console serves the page, and a
# headless chromium (console_latency.js) collects the age of every new pose at its arrival in the
# page (writer's source timestamp to the page's WebSocket handler, one machine clock). Prints
# the figures; asserts nothing.
#
#   console_latency_bench.sh BUILD_DIR [ENTITIES (50)] [SECONDS (40)]
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
BUILD=$(cd "${1:?usage: console_latency_bench.sh BUILD_DIR [ENTITIES] [SECONDS]}" && pwd)
ENTITIES=${2:-50}
SECONDS_MEASURED=${3:-40}
export FASTRTPS_DEFAULT_PROFILES_FILE=$REPO/deploy/dds/pena-loopback.xml
WORK=$(mktemp -d /tmp/pena-console-latency.XXXXXX)
PIDS=()
cleanup() {
  local pid
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$WORK"
}
trap cleanup EXIT

# shellcheck source=../../deploy/dds/domain-lock.sh
source "$REPO/deploy/dds/domain-lock.sh"
pena_lock_dds_domain DOMAIN

"$BUILD/tools/pena/pena" simulate --scenario team --seed 1 --out "$WORK/team" > /dev/null
"$BUILD/services/console/pena-console" --port 0 --port-file "$WORK/port" --domain "$DOMAIN" \
  --profiles-file "$REPO/deploy/dds/pena-loopback.xml" --profiles-file "$REPO/deploy/dds/pena-qos.xml" \
  > "$WORK/console.log" 2>&1 &
CONSOLE=$!
PIDS+=("$CONSOLE")
for _ in $(seq 100); do [[ -s $WORK/port ]] && break; sleep 0.1; done
# Mission seconds replayed: enough for the measurement, the warm-up and the load's set-up.
"$BUILD/services/bench/pena-load" --mission "$WORK/team" --entities "$ENTITIES" \
  --duration $((SECONDS_MEASURED + 40)) --domain "$DOMAIN" --work "$WORK/load" \
  --fusion "$BUILD/services/fusion/pena-fusion" > "$WORK/load.log" 2>&1 &
PIDS+=("$!")
cpu0=$(awk '{print $14 + $15}' "/proc/$CONSOLE/stat")
node "$HERE/console_latency.js" --url "http://127.0.0.1:$(cat "$WORK/port")/" --seconds "$SECONDS_MEASURED"
cpu1=$(awk '{print $14 + $15}' "/proc/$CONSOLE/stat")
awk -v t="$(( cpu1 - cpu0 ))" -v hz="$(getconf CLK_TCK)" -v s="$SECONDS_MEASURED" \
  'BEGIN { printf "pena-console CPU: %.1f s in the run (warm-up and %s s measured)\n", t / hz, s }'
