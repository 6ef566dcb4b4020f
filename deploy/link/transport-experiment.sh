#!/usr/bin/env bash
# The transport measurement of docs/gateway.md: the same gateway, scheduler and synthetic team
# over UDP and over TCP, through the same shaped link with a silent 30 s outage, at each rate
# given (kbit/s). Runs the pairs in parallel (separate namespaces) and prints a Markdown table.
# Both transports carry open frames (--insecure-link): TCP carries no sealed ones, and the
# measurement compares transports, not the seal (docs/security.md).
# usage: transport-experiment.sh [--gateway PATH] [--out DIR] [RATE_KBIT ...]   (default 9.6)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
gateway_args=(); out_dir=/tmp/pena-transport-$$; rates=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --gateway) gateway_args=(--gateway "$2"); shift 2;;
    --out) out_dir="$2"; shift 2;;
    *) rates+=("$1"); shift;;
  esac
done
[[ ${#rates[@]} -gt 0 ]] || rates=(9.6)
mkdir -p "$out_dir"
pids=()
for rate in "${rates[@]}"; do
  for transport in udp tcp; do
    "$here/run-link.sh" "${gateway_args[@]}" --insecure-link --rate-kbit "$rate" --transport "$transport" \
      --duration-s 150 --outage 40:70 --map-until-s 90 --out "$out_dir/$transport-$rate" \
      > "$out_dir/$transport-$rate.json" 2> "$out_dir/$transport-$rate.err" & pids+=($!)
  done
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
python3 - "$out_dir" "${rates[@]}" <<'PY'
import json, sys
out, rates = sys.argv[1], sys.argv[2:]
print("| kbit/s | transport | pose age p50 / p99 / max (s) | longest pose gap (s) | maps equal | map converged after last change (s) | near->far bytes |")
print("|---|---|---|---|---|---|---|")
for rate in rates:
    for t in ("udp", "tcp"):
        try:
            r = json.load(open(f"{out}/{t}-{rate}.json"))
        except (OSError, ValueError):
            print(f"| {rate} | {t} | run failed, see {out}/{t}-{rate}.err | | | | |"); continue
        print(f"| {rate} | {t} | {r['pose_age_p50_s']:.2f} / {r['pose_age_p99_s']:.2f} / {r['pose_age_max_s']:.2f} "
              f"| {r['max_pose_gap_s']:.1f} | {r['maps_equal']} | {r['map_converged_after_last_change_s']:.1f} "
              f"| {r['near_wire_bytes']} |")
PY
exit $status
