#!/usr/bin/env bash
# The PeNa team demo (docs/demo.md): the built-in `team` mission (three firefighters, one robot,
# a partial a priori plan) with one pena-entity per member and one pena-fusion, on loopback DDS,
# time running PENA_DEMO_RATE (default 5) times faster than real time; then `pena report`.
#
#   deploy/demo/run-team.sh OUT_DIR
#
# Environment: PENA_BUILD (build tree, default <repo>/build), PENA_DEMO_RATE (5), PENA_DEMO_SEED
# (1), PENA_DEMO_MISSION (reuse an existing `pena simulate` output instead of simulating, or replay
# a recorded mission without ground truth: one directory per entity holding sensors.penalog or
# pena-entity --record's recording/sensors.penalog, apriori.csv beside them if there is a plan;
# then there is no report, the picture is OUT/console.png and OUT/console.svg),
# PENA_DDS_DOMAIN (default: the first free of 30..99, locked with /tmp/pena-dds-domain-N.lock),
# PENA_FUSION_ARGS (extra pena-fusion options, e.g. --no-corrections or --raw-corrections to
# compare with the filtered corrections), PENA_DEMO_LOCKSTEP (1: fusion and entities in lockstep,
# so the corrections and the map do not depend on the machine's load; 0: free-running, as a real
# deployment; off by itself with --no-corrections, where there is no answer to wait for),
# PENA_DEMO_CORRECTION_INTERVAL (2.4: mission seconds between correction attempts per entity),
# PENA_ENTITY_CONFIG (an EntityConfig file every pena-entity reads first; its command line wins,
# e.g. `pipeline { spread_strides: true }`, docs/services.md), PENA_ENTITY_ARGS (extra
# pena-entity options for every entity, e.g. `--hold-at 17,22`), PENA_DEMO_CONSOLE (1: serve
# pena-console, if built, while the team runs, and write OUT/console.png, a headless chromium's
# screenshot of it at the end; 0: no console), PENA_DEMO_CONSOLE_PORT (8090; on 127.0.0.1),
# PENA_DEMO_SECURE (1: DDS Security, every process with its own identity made for the run by
# deploy/security/make-identities.sh into OUT/security; 0, the default: an open domain;
# docs/security.md says why).
# Every process started here is stopped on exit (normal, error, Ctrl-C); nothing is left running.
set -euo pipefail

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
BUILD=${PENA_BUILD:-$REPO/build}
OUT=${1:?usage: run-team.sh OUT_DIR}
RATE=${PENA_DEMO_RATE:-5}
LOCKSTEP=${PENA_DEMO_LOCKSTEP:-1}
[[ " ${PENA_FUSION_ARGS:-} " == *" --no-corrections "* ]] && LOCKSTEP=0
SEED=${PENA_DEMO_SEED:-1}
SECURE=${PENA_DEMO_SECURE:-0}
INTERVAL=${PENA_DEMO_CORRECTION_INTERVAL:-2.4}
PENA=$BUILD/tools/pena/pena
FUSION_BIN=$BUILD/services/fusion/pena-fusion
ENTITY_BIN=$BUILD/services/entity/pena-entity
DDS_DIR=$REPO/deploy/dds
# Every participant, ours and Fast DDS's defaults, stays on the loopback interface.
export FASTRTPS_DEFAULT_PROFILES_FILE=$DDS_DIR/pena-loopback.xml

for bin in "$PENA" "$FUSION_BIN" "$ENTITY_BIN"; do
  [[ -x $bin ]] || { echo "run-team.sh: $bin not built (make pena pena-fusion pena-entity)" >&2; exit 1; }
done

PIDS=()
cleanup() {
  local pid
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for _ in $(seq 50); do
    local alive=0
    for pid in "${PIDS[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${PIDS[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT
trap 'exit 130' INT TERM

if [[ -z ${PENA_DDS_DOMAIN:-} ]]; then
  # shellcheck source=../dds/domain-lock.sh
  source "$REPO/deploy/dds/domain-lock.sh"
  pena_lock_dds_domain PENA_DDS_DOMAIN
fi
DOMAIN=${PENA_DDS_DOMAIN:?no free DDS domain in 30..99}

mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
rm -rf "$OUT/fusion" "$OUT/logs"
mkdir -p "$OUT/fusion" "$OUT/logs"
START=$SECONDS

MISSION=${PENA_DEMO_MISSION:-$OUT/mission}
if [[ -z ${PENA_DEMO_MISSION:-} ]]; then
  echo "== simulating the team mission (seed $SEED) into $MISSION"
  "$PENA" simulate --scenario team --seed "$SEED" --out "$MISSION" > "$OUT/logs/simulate.log"
fi
MISSION=$(cd "$MISSION" && pwd)

# An entity's log: a simulated mission's sensors.penalog, or what pena-entity --record kept.
entity_log() {
  local dir=${1%/}
  if [[ -f $dir/sensors.penalog ]]; then
    echo "$dir/sensors.penalog"
  elif [[ -f $dir/recording/sensors.penalog ]]; then
    echo "$dir/recording/sensors.penalog"
  fi
}
TEAM_IDS=()
for dir in "$MISSION"/*/; do [[ -n $(entity_log "$dir") ]] && TEAM_IDS+=("$(basename "$dir")"); done
((${#TEAM_IDS[@]})) || { echo "run-team.sh: no entity log (*/sensors.penalog, */recording/sensors.penalog) in $MISSION" >&2; exit 1; }
SEC=$OUT/security
if ((SECURE)); then
  # The mission's CAs and one identity per process; kept across runs into the same OUT.
  bash "$REPO/deploy/security/make-identities.sh" "$SEC" "${TEAM_IDS[@]}" > "$OUT/logs/security.log"
  echo "== DDS Security: identities for ${TEAM_IDS[*]}, fusion, operator in $SEC"
fi

cat > "$OUT/fusion.conf" <<CONF
# pena-fusion config of this demo run (FusionConfig, docs/fusion-service.md)
state_dir: "fusion/state"
$([[ -f $MISSION/apriori.csv ]] && echo "plan: \"$MISSION/apriori.csv\"")
output_dir: "fusion"
$(if ((LOCKSTEP)); then
  echo "# Lockstep: attempt a correction at most every $INTERVAL s of mission time per entity; every"
  echo "# entity waits for the answer (--await-corrections $INTERVAL), so a busy machine cannot drop one."
  echo "correction_interval_s: $INTERVAL"
else
  echo "# Attempt a correction at most every 0.2 wall s per entity (1 s of mission time at rate 5)."
  echo "correction_interval_s: 0.2"
fi)
dds {
  profiles_files: "$DDS_DIR/pena-loopback.xml"
  profiles_files: "$DDS_DIR/pena-qos.xml"
  domain_id: $DOMAIN
$( ((SECURE)) && echo "  security_dir: \"$SEC/fusion\"")
}
CONF

FUSION_ARGS=()
ENTITY_ARGS=()
if ((LOCKSTEP)); then
  # The team's ids: the fusion orders their samples by mission time once all four are heard.
  TEAM=$(IFS=,; echo "${TEAM_IDS[*]}")
  FUSION_ARGS=(--lockstep --lockstep-entities "$TEAM")
  ENTITY_ARGS=(--await-corrections "$INTERVAL")
fi
if [[ -n ${PENA_ENTITY_CONFIG:-} ]]; then ENTITY_ARGS+=(--config "$(realpath "$PENA_ENTITY_CONFIG")"); fi
echo "== pena-fusion (DDS domain $DOMAIN, loopback only$( ((LOCKSTEP)) && echo ", lockstep")$( ((SECURE)) && echo ", DDS Security"))"
# shellcheck disable=SC2086  # PENA_FUSION_ARGS is a list of options
"$FUSION_BIN" --config "$OUT/fusion.conf" "${FUSION_ARGS[@]}" ${PENA_FUSION_ARGS:-} \
  > "$OUT/logs/fusion.log" 2>&1 &
FUSION_PID=$!
PIDS+=("$FUSION_PID")

CONSOLE_BIN=$BUILD/services/console/pena-console
CONSOLE_URL=""
if [[ ${PENA_DEMO_CONSOLE:-1} == 1 && -x $CONSOLE_BIN ]]; then
  rm -f "$OUT/logs/console.port"
  "$CONSOLE_BIN" --port "${PENA_DEMO_CONSOLE_PORT:-8090}" --port-file "$OUT/logs/console.port" \
    --domain "$DOMAIN" --profiles-file "$DDS_DIR/pena-loopback.xml" \
    --profiles-file "$DDS_DIR/pena-qos.xml" \
    $( ((SECURE)) && echo "--profiles-file $SEC/operator/dds-profile.xml --profile pena_loopback_secure") \
    > "$OUT/logs/console.log" 2>&1 &
  PIDS+=("$!")
  for _ in $(seq 50); do [[ -s $OUT/logs/console.port ]] && break; sleep 0.1; done
  if [[ -s $OUT/logs/console.port ]]; then
    CONSOLE_URL="http://127.0.0.1:$(cat "$OUT/logs/console.port")/"
    echo "== pena-console: open $CONSOLE_URL to watch the team (docs/console.md)"
  else
    echo "run-team.sh: pena-console did not start (see $OUT/logs/console.log); going on without it"
  fi
fi

ENTITY_PIDS=()
ENTITIES=()
for id in "${TEAM_IDS[@]}"; do
  ENTITIES+=("$id")
  rm -rf "${OUT:?}/$id"
  # shellcheck disable=SC2086  # PENA_ENTITY_ARGS is a list of options
  "$ENTITY_BIN" --input "$(entity_log "$MISSION/$id")" --rate "$RATE" --out "$OUT/$id" --domain "$DOMAIN" \
    --profiles-file "$DDS_DIR/pena-loopback.xml" --profiles-file "$DDS_DIR/pena-qos.xml" \
    --wait-for-readers 20 --linger 5 "${ENTITY_ARGS[@]}" ${PENA_ENTITY_ARGS:-} \
    $( ((SECURE)) && echo "--security $SEC/$id") > "$OUT/logs/$id.log" 2>&1 &
  ENTITY_PIDS+=("$!")
  PIDS+=("$!")
done
echo "== ${#ENTITIES[@]} pena-entity processes (${ENTITIES[*]}) at $RATE x real time"

failed=0
for i in "${!ENTITY_PIDS[@]}"; do
  if ! wait "${ENTITY_PIDS[$i]}"; then
    echo "run-team.sh: pena-entity ${ENTITIES[$i]} failed; see $OUT/logs/${ENTITIES[$i]}.log" >&2
    failed=1
  fi
done
# Let the fusion take the last deltas and snapshots, then stop it cleanly (it writes its outputs).
sleep 2
SHOT=$REPO/tests/console/console_shot.js
if [[ -n $CONSOLE_URL && -d $REPO/tests/console/node_modules/puppeteer-core ]] &&
  command -v chromium >/dev/null && command -v node >/dev/null; then
  # The page as the operator saw it, and the map alone as SVG (the page's "SVG" export).
  if node "$SHOT" --url "$CONSOLE_URL" --out "$OUT/console.png" > "$OUT/logs/console_shot.log" 2>&1 &&
    node "$SHOT" --url "$CONSOLE_URL" --out "$OUT/console.svg" >> "$OUT/logs/console_shot.log" 2>&1; then
    echo "== console screenshot: $OUT/console.png, the map as SVG: $OUT/console.svg"
  else
    echo "run-team.sh: no console screenshot (see $OUT/logs/console_shot.log)"
  fi
fi
kill -TERM "$FUSION_PID"
if ! wait "$FUSION_PID"; then
  echo "run-team.sh: pena-fusion failed; see $OUT/logs/fusion.log" >&2
  exit 1
fi
((failed == 0)) || exit 1
if ! compgen -G "$MISSION/*/truth.tum" > /dev/null; then
  # A real mission: nothing to score against; the console's picture is the result.
  echo "== mission finished in $((SECONDS - START)) s; no ground truth in $MISSION, so no report"
  echo "== output: $OUT (fusion/global_map.csv, <entity>/trajectory.tum$(
    [[ -f $OUT/console.png ]] && echo ", console.png, console.svg"))"
  exit 0
fi
echo "== mission finished in $((SECONDS - START)) s; writing the report"

"$PENA" report --mission "$MISSION" --run "$OUT" | tee "$OUT/logs/report.log"
echo "== demo output: $OUT (report.md, report.json, global_map.png/.svg/.csv, <entity>/trajectory.tum$(
  [[ -f $OUT/console.png ]] && echo ", console.png, console.svg"))"
