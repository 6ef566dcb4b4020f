#!/usr/bin/env bash
# The operator's traffic across the radio link, in real browsers: the team mission (lockstep,
# 2x real time, deploy/demo/run-team.sh) with pena-fusion and a pena-console in a "building"
# network namespace, a pena-console at the "command post" in another, and a sealed pena-gateway
# pair between their DDS domains over a 9.6 kbit/s link (tc tbf in a third namespace,
# deploy/link/netns-lib.sh). console_gateway_test.js drives one chromium in each namespace.
#
#   console_gateway_test.sh BUILD_DIR
#
# Without root, ip or tc (no namespaces) both sides share this machine's loopback, and the
# gateways' own bit budget (8640 bit/s) and an emulated 0.1 s delay stand for the radio: the
# script says so. Exit 77 (skipped) without chromium or tests/console/node_modules. Leaves its
# logs, figures and screenshots in $PENA_CONSOLE_TEST_OUT (default: a temporary directory,
# removed on success).
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
BUILD=$(cd "${1:?usage: console_gateway_test.sh BUILD_DIR}" && pwd)
CHROMIUM=${PENA_CHROMIUM:-$(command -v chromium || true)}
if [[ -z $CHROMIUM || ! -d $HERE/node_modules/puppeteer-core ]] || ! command -v node >/dev/null; then
  echo "console_gateway_test: chromium, node or tests/console/node_modules missing (scripts/setup.sh installs them); skipped"
  exit 77
fi
export FASTRTPS_DEFAULT_PROFILES_FILE=$REPO/deploy/dds/pena-loopback.xml
GATEWAY=$BUILD/gateway/pena-gateway
CONSOLE=$BUILD/services/console/pena-console
PROFILES=(--profiles-file "$REPO/deploy/dds/pena-loopback.xml" --profiles-file "$REPO/deploy/dds/pena-qos.xml")
GW_PROFILES=(--dds-profiles-file "$REPO/deploy/dds/pena-loopback.xml" --dds-profiles-file "$REPO/deploy/dds/pena-qos.xml")

OUT=${PENA_CONSOLE_TEST_OUT:-$(mktemp -d /tmp/pena-console-gateway.XXXXXX)}
mkdir -p "$OUT"
PIDS=()
NETNS=0
cleanup() {
  local pid
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  ((NETNS)) && link_teardown
  return 0
}
trap cleanup EXIT

# Two DDS domains of our own (deploy/dds/domain-lock.sh): the shared-memory transport of
# pena-loopback.xml reaches across network namespaces, so the two sides need different domains.
# shellcheck source=../../deploy/dds/domain-lock.sh
source "$REPO/deploy/dds/domain-lock.sh"
pena_lock_dds_domain BLD_DOMAIN
pena_lock_dds_domain POST_DOMAIN

IN_BLD=(); IN_POST=(); BLD_NS=""; POST_NS=""
if [[ $(id -u) == 0 ]] && command -v ip >/dev/null && command -v tc >/dev/null; then
  # shellcheck source=../../deploy/link/netns-lib.sh
  source "$REPO/deploy/link/netns-lib.sh"
  NETNS=1
  link_setup "c$(printf '%x' $(( ($$ * 7 + RANDOM) % 4096 )))"
  link_shape 9.6
  IN_BLD=(ip netns exec "$LINK_BLD_NS"); IN_POST=(ip netns exec "$LINK_POST_NS")
  BLD_NS=$LINK_BLD_NS; POST_NS=$LINK_POST_NS
  BLD_ADDR=$LINK_BUILDING_IP:7700; POST_ADDR=$LINK_POST_IP:7700
  LINK_ARGS=(--overhead-bytes 42)
  echo "radio link: network namespaces $LINK_BLD_NS <-> $LINK_RADIO_NS (tc tbf 9.6 kbit/s) <-> $LINK_POST_NS"
else
  BLD_ADDR=127.0.0.1:$((17000 + BLD_DOMAIN * 2)); POST_ADDR=127.0.0.1:$((17001 + BLD_DOMAIN * 2))
  LINK_ARGS=(--emulate-delay-s 0.1)
  echo "radio link: EMULATED on loopback (no root, ip or tc for network namespaces here): the" \
       "gateways' 8640 bit/s budget and a 0.1 s emulated delay, no radio queue"
fi

"$BUILD/tools/pena/pena" simulate --scenario team --seed 1 --out "$OUT/mission" > "$OUT/simulate.log"
# An old run's files in PENA_CONSOLE_TEST_OUT would name dead consoles' ports: gone first.
rm -f "$OUT/post.port" "$OUT/building.port"
"$GATEWAY" --generate-link-key "$OUT/link.key" > /dev/null
GW_COMMON=(--link-key "$OUT/link.key" --budget-bit-s 8640 --duration-s 0 "${LINK_ARGS[@]}" "${GW_PROFILES[@]}")

# The command post: its gateway and console first, so nothing is missed.
"${IN_POST[@]}" "$GATEWAY" "${GW_COMMON[@]}" --bind "$POST_ADDR" --peer "$BLD_ADDR" --name post \
  --stats "$OUT/gateway-post.json" --dds-domain "$POST_DOMAIN" --role command-post \
  > "$OUT/gateway-post.out" 2> "$OUT/gateway-post.log" &
PIDS+=("$!")
"${IN_POST[@]}" "$CONSOLE" --port 0 --port-file "$OUT/post.port" --domain "$POST_DOMAIN" \
  "${PROFILES[@]}" --operator-id post > "$OUT/console-post.log" 2>&1 &
PIDS+=("$!")
"${IN_BLD[@]}" "$GATEWAY" "${GW_COMMON[@]}" --bind "$BLD_ADDR" --peer "$POST_ADDR" --name building \
  --stats "$OUT/gateway-building.json" --dds-domain "$BLD_DOMAIN" --role building \
  > "$OUT/gateway-building.out" 2> "$OUT/gateway-building.log" &
PIDS+=("$!")
"${IN_BLD[@]}" "$CONSOLE" --port 0 --port-file "$OUT/building.port" --domain "$BLD_DOMAIN" \
  "${PROFILES[@]}" --operator-id building > "$OUT/console-building.log" 2>&1 &
PIDS+=("$!")
for _ in $(seq 100); do [[ -s $OUT/post.port && -s $OUT/building.port ]] && break; sleep 0.1; done
if [[ ! -s $OUT/post.port || ! -s $OUT/building.port ]]; then
  echo "console_gateway_test: pena-console wrote no port file in 10 s; see $OUT/console-post.log, $OUT/console-building.log"
  exit 1
fi
POST_PORT=$(cat "$OUT/post.port")
BLD_PORT=$(cat "$OUT/building.port")
echo "command post console on port $POST_PORT (DDS domain $POST_DOMAIN), building console on port $BLD_PORT (DDS domain $BLD_DOMAIN)"

# The team in the building (run-team.sh is told the domain, whose lock is held here).
"${IN_BLD[@]}" env PENA_BUILD="$BUILD" PENA_DEMO_MISSION="$OUT/mission" PENA_DDS_DOMAIN="$BLD_DOMAIN" \
  PENA_DEMO_RATE=2 PENA_DEMO_CONSOLE=0 bash "$REPO/deploy/demo/run-team.sh" "$OUT/run" > "$OUT/team.log" 2>&1 &
PIDS+=("$!")

status=0
node "$HERE/console_gateway_test.js" --post "http://127.0.0.1:$POST_PORT/" --building "http://127.0.0.1:$BLD_PORT/" \
  --post-netns "$POST_NS" --building-netns "$BLD_NS" --out "$OUT" --entities 4 --chromium "$CHROMIUM" 2>&1 |
  tee "$OUT/browser.log" || status=$?
if ((status == 0)); then
  # The rotation is in pena-fusion's journal (synced before it is applied).
  id=$(cat "$OUT/correction_id")
  journal=$(find "$OUT/run" -name operator_corrections.csv | head -n 1)
  if [[ -z $journal ]] || ! grep -q "^$id," "$journal"; then
    echo "FAIL: $id is not in pena-fusion's operator_corrections.csv (${journal:-not found})"
    status=1
  else
    echo "pena-fusion journalled $id: $(grep "^$id," "$journal")"
  fi
fi
cleanup
PIDS=()
NETNS=0
for side in post building; do
  [[ -s $OUT/gateway-$side.json ]] || continue
  python3 - "$OUT/gateway-$side.json" "$side" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
sent = s["sent"]
print(f"gateway {sys.argv[2]}: pose age p50 {s['pose_age_p50_s']:.2f} s, p99 {s['pose_age_p99_s']:.2f} s "
      f"({s['poses_received']} poses received), {s['wire_bytes_sent']} wire bytes sent, "
      f"annotations+operator corrections {sent['annotation']['items']} items "
      f"({sent['annotation']['resent']} resent), rejected {s['frames_rejected']}")
PY
done
if ((status)); then
  echo "console_gateway_test: failed; logs and screenshots in $OUT"
  tail -n 20 "$OUT/console-post.log" "$OUT/gateway-post.log" || true
  exit "$status"
fi
[[ -n ${PENA_CONSOLE_TEST_OUT:-} ]] || rm -rf "$OUT"
