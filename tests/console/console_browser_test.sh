#!/usr/bin/env bash
# The console in a real browser: the team mission (lockstep, loopback DDS, deploy/demo/run-team.sh)
# with pena-console beside it, and Debian's chromium driven by console_browser_test.js.
#
#   console_browser_test.sh BUILD_DIR
#
# Exit 77 (skipped) when chromium or the npm packages (tests/console/node_modules, installed by
# scripts/setup.sh) are missing. Leaves its figures and screenshots in $PENA_CONSOLE_TEST_OUT
# (default: a temporary directory, removed on success). PENA_CONSOLE_TEST_ROTATE=<entity> adds
# the three-point rotation check, done while the team's entities hold their clocks at the mission
# times PENA_CONSOLE_TEST_HOLD_AT (17,22: pena-entity --hold-at; the test releases them);
# PENA_CONSOLE_TEST_FUSION_ARGS goes to pena-fusion (--no-corrections: free-running);
# PENA_CONSOLE_TEST_RATE is the mission's time scale (2).
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
BUILD=$(cd "${1:?usage: console_browser_test.sh BUILD_DIR}" && pwd)
CHROMIUM=${PENA_CHROMIUM:-$(command -v chromium || true)}
if [[ -z $CHROMIUM || ! -d $HERE/node_modules/puppeteer-core ]] || ! command -v node >/dev/null; then
  echo "console_browser_test: chromium, node or tests/console/node_modules missing (scripts/setup.sh installs them); skipped"
  exit 77
fi
export FASTRTPS_DEFAULT_PROFILES_FILE=$REPO/deploy/dds/pena-loopback.xml

OUT=${PENA_CONSOLE_TEST_OUT:-$(mktemp -d /tmp/pena-console-test.XXXXXX)}
mkdir -p "$OUT"
# An old run's files in PENA_CONSOLE_TEST_OUT would name dead consoles' ports: gone first.
rm -f "$OUT/console.port" "$OUT/console2.port"
PIDS=()
cleanup() {
  local pid
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT

# A DDS domain of our own (deploy/dds/domain-lock.sh: parallel runs do not meet).
# shellcheck source=../../deploy/dds/domain-lock.sh
source "$REPO/deploy/dds/domain-lock.sh"
pena_lock_dds_domain DOMAIN

"$BUILD/tools/pena/pena" simulate --scenario team --seed 1 --out "$OUT/mission" > "$OUT/simulate.log"

"$BUILD/services/console/pena-console" --port 0 --port-file "$OUT/console.port" --domain "$DOMAIN" \
  --profiles-file "$REPO/deploy/dds/pena-loopback.xml" --profiles-file "$REPO/deploy/dds/pena-qos.xml" \
  --operator-id test > "$OUT/console.log" 2>&1 &
PIDS+=("$!")
# A second console on the same domain (another operator's command post).
"$BUILD/services/console/pena-console" --port 0 --port-file "$OUT/console2.port" --domain "$DOMAIN" \
  --profiles-file "$REPO/deploy/dds/pena-loopback.xml" --profiles-file "$REPO/deploy/dds/pena-qos.xml" \
  --operator-id second > "$OUT/console2.log" 2>&1 &
PIDS+=("$!")
for _ in $(seq 100); do [[ -s $OUT/console.port && -s $OUT/console2.port ]] && break; sleep 0.1; done
if [[ ! -s $OUT/console.port || ! -s $OUT/console2.port ]]; then
  echo "console_browser_test: pena-console wrote no port file in 10 s; see $OUT/console.log, $OUT/console2.log"
  exit 1
fi
PORT=$(cat "$OUT/console.port")
PORT2=$(cat "$OUT/console2.port")
echo "pena-console on http://127.0.0.1:$PORT/ and http://127.0.0.1:$PORT2/ (DDS domain $DOMAIN)"

# The team at 2x real time: the browser's checks need the mission to last about a minute.
# The domain's lock is held here; run-team.sh is told the domain.
HOLD_AT=""
[[ -n ${PENA_CONSOLE_TEST_ROTATE:-} ]] && HOLD_AT=${PENA_CONSOLE_TEST_HOLD_AT:-17,22}
PENA_ENTITY_ARGS=${HOLD_AT:+--hold-at $HOLD_AT} PENA_BUILD=$BUILD PENA_DEMO_MISSION=$OUT/mission PENA_DDS_DOMAIN=$DOMAIN \
  PENA_DEMO_RATE=${PENA_CONSOLE_TEST_RATE:-2} PENA_FUSION_ARGS=${PENA_CONSOLE_TEST_FUSION_ARGS:-} \
  PENA_DEMO_CONSOLE=0 \
  bash "$REPO/deploy/demo/run-team.sh" "$OUT/run" > "$OUT/team.log" 2>&1 &
TEAM=$!
PIDS+=("$TEAM")

status=0
node "$HERE/console_browser_test.js" --url "http://127.0.0.1:$PORT/" --url2 "http://127.0.0.1:$PORT2/" \
  --out "$OUT" \
  --mission "$OUT/mission" --entities 4 --chromium "$CHROMIUM" \
  ${PENA_CONSOLE_TEST_ROTATE:+--rotate "$PENA_CONSOLE_TEST_ROTATE" --hold-at "$HOLD_AT" --logs "$OUT/run/logs"} 2>&1 | tee "$OUT/browser.log" ||
  status=$?
if ((status)); then
  echo "console_browser_test: failed; logs and screenshots in $OUT"
  tail -n 20 "$OUT/console.log" || true
  exit "$status"
fi
[[ -n ${PENA_CONSOLE_TEST_OUT:-} ]] || rm -rf "$OUT"
