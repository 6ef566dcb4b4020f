#!/usr/bin/env bash
# One link experiment (docs/link-experiments.md): the `team` mission replayed in real time by
# one pena-entity per member plus pena-fusion in a "building" network namespace, a pena-monitor
# at the "command post" in another, a shaped radio link between them (tc tbf in a third
# namespace), and a scheduled outage. Modes:
#   gateway  building DDS domain <-> pena-gateway == link == pena-gateway <-> post DDS domain
#   dds      plain Fast DDS across the link (profiles pena-link-{building,post}.xml), its
#            map and pose writers rate-limited by flow controllers (flow-qos.py)
# A second pena-monitor inside the building gives the reference (poses as written, fusion's map
# versions as published). --secure runs every participant with DDS Security: identities made for
# the run (deploy/security/make-identities.sh into OUT/security), the gateways with the gateway
# identity's profile (docs/security.md). Writes OUT/result.json (analyse-run.py). Needs root,
# ip, tc, python3.
# Every process and namespace it creates is removed on any exit. Nothing leaves the machine.
set -euo pipefail

mode=gateway; rate_kbit=9.6; entity_rate=1; outage=""; delay_s=0; loss=0; settle_s=90
mission=""; out=""; build="${PENA_BUILD:-}"; gateway_extra=(); link_insecure=0; secure=0
usage() {
  cat <<USAGE
usage: $0 --mission DIR --out DIR [--mode gateway|dds] [--rate-kbit 9.6] [--entity-rate 1]
          [--outage START:END] (seconds after the entities start) [--delay-s 0] [--loss 0]
          (gateway mode only: emulated in the receiving gateways, no netem on this kernel)
          [--settle-s 90] (max wait after the entities end for the post's map to converge)
          [--insecure-link] (gateway mode: open frames; default: sealed with a key made for the run)
          [--secure] (DDS Security on every participant, identities made for the run)
          [--build DIR] [-- extra pena-gateway options]
USAGE
}
while [[ $# -gt 0 ]]; do
  case "$1" in
    --mode) mode="$2"; shift 2;;
    --rate-kbit) rate_kbit="$2"; shift 2;;
    --entity-rate) entity_rate="$2"; shift 2;;
    --outage) outage="$2"; shift 2;;
    --delay-s) delay_s="$2"; shift 2;;
    --loss) loss="$2"; shift 2;;
    --settle-s) settle_s="$2"; shift 2;;
    --mission) mission="$2"; shift 2;;
    --out) out="$2"; shift 2;;
    --build) build="$2"; shift 2;;
    --insecure-link) link_insecure=1; shift;;
    --secure) secure=1; shift;;
    --) shift; gateway_extra=("$@"); break;;
    -h|--help) usage; exit 0;;
    *) echo "team-link-run.sh: unknown option '$1'" >&2; usage >&2; exit 2;;
  esac
done
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="${PENA_REPO:-$(cd "$here/../.." && pwd)}"  # link-experiments.sh runs a copy
build="${build:-$repo/build}"
[[ -n $mission && -n $out ]] || { usage >&2; exit 2; }
[[ $mode == gateway || $mode == dds ]] || { echo "team-link-run.sh: --mode gateway|dds" >&2; exit 2; }
[[ $(id -u) == 0 ]] || { echo "team-link-run.sh: needs root (network namespaces)" >&2; exit 77; }
fusion_bin=$build/services/fusion/pena-fusion; entity_bin=$build/services/entity/pena-entity
monitor_bin=$build/services/monitor/pena-monitor; gateway_bin=${PENA_GATEWAY:-$build/gateway/pena-gateway}
bins=("$fusion_bin" "$entity_bin" "$monitor_bin"); [[ $mode == gateway ]] && bins+=("$gateway_bin")
for bin in "${bins[@]}"; do
  [[ -x $bin ]] || { echo "team-link-run.sh: $bin not built" >&2; exit 2; }
done
mission=$(cd "$mission" && pwd)
mkdir -p "$out"; out=$(cd "$out" && pwd)
rm -rf "${out:?}"/{building,post,fusion,logs,entities,gateway,security}; mkdir -p "$out"/{logs,entities,gateway}
dds_dir=$repo/deploy/dds
source "$here/netns-lib.sh"

# DDS domains. dds mode: domain 7 on both sides (the pena-link-*.xml profiles name its ports);
# those participants have no shared-memory transport and the run has its own namespaces, so
# nothing else can meet them. gateway mode: two domains taken with the cooperative lock files
# every PeNa script uses (run-team.sh), because the building and post participants use
# pena-loopback.xml, whose shared-memory transport is visible across network namespaces.
# (The lock fds stay open in this shell until it exits.)
if [[ $mode == dds ]]; then
  bld_domain=7; post_domain=7
else
  bld_domain=""; post_domain=""
  for d in $(seq 30 99); do
    exec {lock_fd}>"/tmp/pena-dds-domain-$d.lock"
    if flock -n "$lock_fd"; then
      if [[ -z $bld_domain ]]; then bld_domain=$d; else post_domain=$d; break; fi
    else
      exec {lock_fd}>&-
    fi
  done
  [[ -n $post_domain ]] || { echo "team-link-run.sh: no two free DDS domains in 30..99" >&2; exit 1; }
fi

pids=(); entity_pids=()
# stop_all: one SIGTERM to each process still running (a second one would kill the services
# before they write their outputs), up to 15 s to finish, then SIGKILL.
stop_all() {
  local pid
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for _ in $(seq 150); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  pids=()
}
cleanup() { stop_all; link_teardown; }
trap cleanup EXIT
trap 'exit 130' INT TERM

tag=$(printf '%x' $(( ($$ * 7 + RANDOM) % 65536 )))
link_setup "$tag"
link_shape "$rate_kbit"
# (No shell function around the background commands: $! must be the service's own pid, as
# `ip netns exec` execs it, so that its one SIGTERM reaches it.)
in_bld=(ip netns exec "$LINK_BLD_NS"); in_post=(ip netns exec "$LINK_POST_NS")

# DDS profiles per side.
if [[ $mode == dds ]]; then
  qos=$out/flow-qos.xml
  entities=$(find "$mission" -mindepth 2 -maxdepth 2 -name sensors.penalog | wc -l)
  python3 "$here/flow-qos.py" "$rate_kbit" "$entities" "$dds_dir/pena-qos.xml" "$qos"
  bld_files=(--profiles-file "$dds_dir/pena-link-building.xml" --profiles-file "$qos")
  bld_profile=pena_link_building; bld_env=$dds_dir/pena-link-building.xml
  post_files=(--profiles-file "$dds_dir/pena-link-post.xml" --profiles-file "$dds_dir/pena-qos.xml")
  post_profile=pena_link_post; post_env=$dds_dir/pena-link-post.xml
else
  bld_files=(--profiles-file "$dds_dir/pena-loopback.xml" --profiles-file "$dds_dir/pena-qos.xml")
  bld_profile=pena_loopback; bld_env=$dds_dir/pena-loopback.xml
  post_files=("${bld_files[@]}"); post_profile=pena_loopback; post_env=$bld_env
fi

# DDS Security: one identity per entity of the mission and per role; each process gets its own
# (--security DIR), the gateways the gateway identity's participant profile.
sec_monitor=(); sec_fusion=()
if ((secure)); then
  ids=()
  for dir in "$mission"/*/; do [[ -f $dir/sensors.penalog ]] && ids+=("$(basename "$dir")"); done
  "$repo/deploy/security/make-identities.sh" "$out/security" "${ids[@]}" > "$out/logs/security.log"
  sec_monitor=(--security "$out/security/monitor"); sec_fusion=(--security "$out/security/fusion")
  gw_security_profile=$out/security/gateway/dds-profile.xml
fi

start_ns=$(date +%s%N)
echo "{\"mode\": \"$mode\", \"rate_kbit\": $rate_kbit, \"entity_rate\": $entity_rate, \"outage\": \"$outage\"," \
     "\"delay_s\": $delay_s, \"loss\": $loss, \"building_domain\": $bld_domain, \"post_domain\": $post_domain," \
     "\"start_ns\": $start_ns}" > "$out/run.json"

# Command post: its monitor (and gateway) first, so nothing is missed.
"${in_post[@]}" env FASTRTPS_DEFAULT_PROFILES_FILE="$post_env" "$monitor_bin" --out "$out/post" \
  --domain "$post_domain" --profile "$post_profile" "${post_files[@]}" "${sec_monitor[@]}" \
  > "$out/logs/monitor-post.log" 2>&1 & pids+=($!)
"${in_bld[@]}" env FASTRTPS_DEFAULT_PROFILES_FILE="$bld_env" "$monitor_bin" --out "$out/building" \
  --domain "$bld_domain" --profile "$bld_profile" "${bld_files[@]}" "${sec_monitor[@]}" \
  > "$out/logs/monitor-building.log" 2>&1 & pids+=($!)
if [[ $mode == gateway ]]; then
  source "$here/gateway-args.sh"
  gateway_pair_args "$rate_kbit" "$delay_s" "$loss"
  "${in_post[@]}" env FASTRTPS_DEFAULT_PROFILES_FILE="$post_env" "$gateway_bin" "${gw_post_args[@]}" \
    "${gateway_extra[@]}" > "$out/logs/gateway-post.out" 2> "$out/logs/gateway-post.log" & pids+=($!)
  "${in_bld[@]}" env FASTRTPS_DEFAULT_PROFILES_FILE="$bld_env" "$gateway_bin" "${gw_bld_args[@]}" \
    "${gateway_extra[@]}" > "$out/logs/gateway-building.out" 2> "$out/logs/gateway-building.log" & pids+=($!)
fi
"${in_bld[@]}" env FASTRTPS_DEFAULT_PROFILES_FILE="$bld_env" nice "$fusion_bin" --state-dir "$out/fusion/state" \
  --plan "$mission/apriori.csv" --out "$out/fusion" --domain "$bld_domain" --profile "$bld_profile" \
  "${bld_files[@]}" "${sec_fusion[@]}" > "$out/logs/fusion.log" 2>&1 &
fusion_pid=$!; pids+=($fusion_pid)
sleep 2
entities_start_ns=$(date +%s%N)
for dir in "$mission"/*/; do
  [[ -f $dir/sensors.penalog ]] || continue
  id=$(basename "$dir")
  sec_entity=(); ((secure)) && sec_entity=(--security "$out/security/$id")
  "${in_bld[@]}" env FASTRTPS_DEFAULT_PROFILES_FILE="$bld_env" nice "$entity_bin" --input "$dir" \
    --rate "$entity_rate" --out "$out/entities/$id" --domain "$bld_domain" --profile "$bld_profile" \
    "${bld_files[@]}" "${sec_entity[@]}" --wait-for-readers 20 --linger 5 > "$out/logs/entity-$id.log" 2>&1 &
  entity_pids+=($!); pids+=($!)
done
if [[ -n $outage ]]; then
  ( sleep "${outage%%:*}"; link_blackhole; date +%s%N > "$out/outage-start-ns"
    sleep "$(awk "BEGIN{print ${outage##*:} - ${outage%%:*}}")"; link_shape "$rate_kbit"
    date +%s%N > "$out/outage-end-ns" ) &
  pids+=($!)
fi
failed=0
for pid in "${entity_pids[@]}"; do wait "$pid" || failed=1; done
entities_end_ns=$(date +%s%N)
((failed == 0)) || echo "team-link-run.sh: a pena-entity failed; see $out/logs" >&2

# Settle: until the post's map holds fusion's last published version (fusion's
# global_versions.csv) for 3 s in a row, or settle_s.
fusion_version() { tail -n 1 "$out/fusion/global_versions.csv" 2>/dev/null | cut -d, -f2; }
post_version() { tail -n 1 "$out/post/map.csv" 2>/dev/null | cut -d, -f6; }
equal_since=0
for _ in $(seq "$settle_s"); do
  sleep 1
  f=$(fusion_version); p=$(post_version)
  if [[ -n $f && $f == "$p" ]]; then
    equal_since=$((equal_since + 1)); ((equal_since >= 3)) && break
  else
    equal_since=0
  fi
done
link_counters "$out/link-counters.json"
end_ns=$(date +%s%N)
# Stop fusion first (it writes global_map.csv), then the monitors and gateways.
kill -TERM "$fusion_pid"
fusion_status=0; wait "$fusion_pid" || fusion_status=$?
((fusion_status == 0)) || echo "team-link-run.sh: pena-fusion exit status $fusion_status" >&2
stop_all
cat > "$out/times.json" <<JSON
{"start_ns": $start_ns, "entities_start_ns": $entities_start_ns, "entities_end_ns": $entities_end_ns, "end_ns": $end_ns}
JSON
link_teardown
python3 "$here/analyse-run.py" "$out" "$monitor_bin" > "$out/result.json"
cat "$out/result.json"
