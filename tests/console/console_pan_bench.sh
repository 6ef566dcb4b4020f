#!/usr/bin/env bash
# Frame rate of the console's page while it pans over a large map: pena-console serves the page
# (on a DDS domain of its own, no team), console_pan.js fills the page's map with SEGMENTS
# random walls (a building-sized grid of rooms) and pans it in headless chromium for SECONDS,
# timing every animation frame. Prints the figures; asserts nothing. PENA_PAN_ARGS="--dashed no"
# draws every wall solid.
#
#   console_pan_bench.sh BUILD_DIR [SEGMENTS (10000)] [SECONDS (10)]
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
BUILD=$(cd "${1:?usage: console_pan_bench.sh BUILD_DIR [SEGMENTS] [SECONDS]}" && pwd)
SEGMENTS=${2:-10000}
SECONDS_MEASURED=${3:-10}
export FASTRTPS_DEFAULT_PROFILES_FILE=$REPO/deploy/dds/pena-loopback.xml
WORK=$(mktemp -d /tmp/pena-console-pan.XXXXXX)
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
"$BUILD/services/console/pena-console" --port 0 --port-file "$WORK/port" --domain "$DOMAIN" \
  --profiles-file "$REPO/deploy/dds/pena-loopback.xml" --profiles-file "$REPO/deploy/dds/pena-qos.xml" \
  > "$WORK/console.log" 2>&1 &
PIDS+=("$!")
for _ in $(seq 100); do [[ -s $WORK/port ]] && break; sleep 0.1; done
node "$HERE/console_pan.js" --url "http://127.0.0.1:$(cat "$WORK/port")/" --segments "$SEGMENTS" \
  --seconds "$SECONDS_MEASURED" ${PENA_PAN_ARGS:-} --chromium "${PENA_CHROMIUM:-$(command -v chromium)}"
