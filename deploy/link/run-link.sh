#!/usr/bin/env bash
# Two pena-gateway endpoints across a shaped link between network namespaces (docs/gateway.md,
# "Link harness"). Creates three namespaces (near, radio, far) and two veth pairs itself, shapes
# both directions with tc tbf in the radio namespace, optionally blacks the link out for an
# outage (or takes it down: --outage-mode linkdown), runs a synthetic team on the near side
# and a receiving gateway on the far side, compares their maps, and removes everything on exit.
# Nothing leaves the machine: the namespaces are connected only to each other. Needs root, ip, tc.
#
# This kernel has no netem (tc qdisc ... netem: "Specified qdisc kind is unknown") and no tc
# classifiers or actions, so delay and loss are emulated inside the receiving gateway
# (--emulate-delay-s, --emulate-loss: pena::gateway::EmulatedLink on the receive path).
set -euo pipefail

rate_kbit=9.6; transport=udp; duration_s=120; entities=4; outage=""; delay_s=0; loss=0
map_until_s=60; out_dir=""; gateway="${PENA_GATEWAY:-}"; extra=(); outage_mode=blackhole
insecure=0
usage() {
  cat <<USAGE
usage: $0 [--rate-kbit 9.6] [--transport udp|tcp] [--duration-s 120] [--entities 4]
          [--outage START:END] [--outage-mode blackhole|linkdown] [--delay-s 0] [--loss 0]
          [--map-until-s 60] [--out DIR] [--insecure-link]
          [--gateway PATH] [-- extra pena-gateway options for both ends]
The link is sealed with a key made for the run (OUT/link.key; docs/security.md) unless
--insecure-link. TCP carries open frames only, so --transport tcp implies --insecure-link.
USAGE
}
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rate-kbit) rate_kbit="$2"; shift 2;;
    --transport) transport="$2"; shift 2;;
    --duration-s) duration_s="$2"; shift 2;;
    --entities) entities="$2"; shift 2;;
    --outage) outage="$2"; shift 2;;
    --outage-mode) outage_mode="$2"; shift 2;;
    --delay-s) delay_s="$2"; shift 2;;
    --loss) loss="$2"; shift 2;;
    --map-until-s) map_until_s="$2"; shift 2;;
    --out) out_dir="$2"; shift 2;;
    --gateway) gateway="$2"; shift 2;;
    --insecure-link) insecure=1; shift;;
    --) shift; extra=("$@"); break;;
    -h|--help) usage; exit 0;;
    *) echo "run-link.sh: unknown option '$1'" >&2; usage >&2; exit 2;;
  esac
done
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [[ -z "$gateway" ]]; then
  for candidate in "$here/../../build/gateway/pena-gateway" "$here"/../../build-*/gateway/pena-gateway; do
    [[ -x "$candidate" ]] && { gateway="$candidate"; break; }
  done
fi
[[ -x "$gateway" ]] || { echo "run-link.sh: pena-gateway not found; build it or pass --gateway" >&2; exit 2; }
[[ "$transport" == udp || "$transport" == tcp ]] || { echo "run-link.sh: --transport udp|tcp" >&2; exit 2; }
out_dir="${out_dir:-/tmp/pena-link-$$}"
mkdir -p "$out_dir"

tag=$$
near_ns="pena-near-$tag"; radio_ns="pena-radio-$tag"; far_ns="pena-far-$tag"
near_if="pn$tag"; radio_near_if="rn$tag"; radio_far_if="rf$tag"; far_if="pf$tag"
near_ip=10.77.1.1; radio_near_ip=10.77.1.2; radio_far_ip=10.77.2.1; far_ip=10.77.2.2; port=7700
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  for ns in "$near_ns" "$radio_ns" "$far_ns"; do ip netns del "$ns" 2>/dev/null || true; done
}
trap cleanup EXIT INT TERM

# near <-> radio <-> far. The radio namespace is the link: it forwards between two veth pairs
# and shapes (and blackholes) on its own egress queues, so both gateways see a remote
# bottleneck and silent loss, as with a radio modem, not local qdisc drops.
for ns in "$near_ns" "$radio_ns" "$far_ns"; do ip netns add "$ns"; ip -n "$ns" link set lo up; done
ip link add "$near_if" netns "$near_ns" type veth peer name "$radio_near_if" netns "$radio_ns"
ip link add "$far_if" netns "$far_ns" type veth peer name "$radio_far_if" netns "$radio_ns"
ip -n "$near_ns" addr add "$near_ip/30" dev "$near_if"
ip -n "$radio_ns" addr add "$radio_near_ip/30" dev "$radio_near_if"
ip -n "$radio_ns" addr add "$radio_far_ip/30" dev "$radio_far_if"
ip -n "$far_ns" addr add "$far_ip/30" dev "$far_if"
for spec in "$near_ns:$near_if" "$radio_ns:$radio_near_if" "$radio_ns:$radio_far_if" "$far_ns:$far_if"; do
  ip -n "${spec%%:*}" link set "${spec##*:}" up
done
ip -n "$near_ns" route add default via "$radio_near_ip"
ip -n "$far_ns" route add default via "$radio_far_ip"
ip netns exec "$radio_ns" sysctl -q -w net.ipv4.ip_forward=1

rate_bit=$(awk "BEGIN{print int($rate_kbit*1000)}")
peak_bit=$(awk "BEGIN{print int($rate_kbit*1010)}")
# shape DEV: tbf is the bottleneck. burst holds one full-size packet; peakrate (1 % above rate,
# per packet of at most mtu) makes each packet take its serialisation time, as on a radio,
# instead of passing a burst at veth speed; latency bounds the queue (tail drop beyond it).
shape() {
  ip netns exec "$radio_ns" tc qdisc replace dev "$1" root tbf rate "${rate_bit}bit" burst 1600 \
    latency 2s peakrate "${peak_bit}bit" mtu 1600
}
# blackhole DEV: a radio fade. tbf drops every packet larger than its 10-byte burst.
blackhole() { ip netns exec "$radio_ns" tc qdisc replace dev "$1" root tbf rate 8bit burst 10 latency 1ms; }
shape "$radio_near_if"
shape "$radio_far_if"

# The gateways budget 90 % of the link rate and count IPv4 + UDP + Ethernet headers (42 bytes),
# as tbf does.
budget=$(awk "BEGIN{print $rate_kbit*1000*0.9}")
common=(--budget-bit-s "$budget" --overhead-bytes 42 --duration-s "$duration_s"
        --emulate-delay-s "$delay_s" --emulate-loss "$loss")
[[ "$transport" == tcp ]] && insecure=1
if ((insecure)); then
  common+=(--insecure-link)
else
  rm -f "$out_dir/link.key"
  "$gateway" --generate-link-key "$out_dir/link.key" > /dev/null
  common+=(--link-key "$out_dir/link.key")
fi
far_args=(--bind "$far_ip:$port" --peer "$near_ip:$port" --name far --stats "$out_dir/far.json")
near_args=(--bind "$near_ip:$port" --peer "$far_ip:$port" --name near --stats "$out_dir/near.json"
           --team "$entities" --map-until-s "$map_until_s")
if [[ "$transport" == tcp ]]; then
  # TCP is reliable itself: the gateway's own resends would only duplicate bytes in the stream.
  far_args+=(--tcp --tcp-listen); near_args+=(--tcp)
  common+=(--retransmit-timeout-s 60 --max-retransmit-timeout-s 120)
fi
ip netns exec "$far_ns" "$gateway" "${common[@]}" "${far_args[@]}" "${extra[@]}" \
  > "$out_dir/far.out" 2> "$out_dir/far.log" & pids+=($!)
sleep 0.2
ip netns exec "$near_ns" "$gateway" "${common[@]}" "${near_args[@]}" "${extra[@]}" \
  > "$out_dir/near.out" 2> "$out_dir/near.log" & pids+=($!)
if [[ -n "$outage" ]]; then
  start_s="${outage%%:*}"; length_s=$(awk "BEGIN{print ${outage##*:} - ${outage%%:*}}")
  if [[ "$outage_mode" == linkdown ]]; then
    ( sleep "$start_s"; ip -n "$radio_ns" link set "$radio_far_if" down
      sleep "$length_s"; ip -n "$radio_ns" link set "$radio_far_if" up ) &
  else
    ( sleep "$start_s"; blackhole "$radio_near_if"; blackhole "$radio_far_if"
      sleep "$length_s"; shape "$radio_near_if"; shape "$radio_far_if" ) &
  fi
  pids+=($!)
fi
wait "${pids[0]}" "${pids[1]}"

python3 - "$out_dir" "$rate_kbit" "$transport" "$outage" "$outage_mode" <<'PY'
import json, sys
out, rate, transport, outage, mode = sys.argv[1:]
near = json.load(open(f"{out}/near.json")); far = json.load(open(f"{out}/far.json"))
equal = near["maps"] == far["maps"]
converged = far["last_map_change_s"] - near["last_map_change_s"]
sent = near["sent"]
print(json.dumps({
  "rate_kbit": float(rate), "transport": transport, "outage": outage, "outage_mode": mode,
  "sealed": near["sealed"] and far["sealed"], "near_seal_bytes": near["seal_bytes_sent"],
  "maps_equal": equal, "maps": len(near["maps"]),
  "map_converged_after_last_change_s": round(converged, 2),
  "pose_age_p50_s": round(far["pose_age_p50_s"], 3), "pose_age_p99_s": round(far["pose_age_p99_s"], 3),
  "pose_age_max_s": round(far["pose_age_max_s"], 3), "max_pose_gap_s": round(far["max_pose_gap_s"], 2),
  "poses_received": far["poses_received"], "alarms_received": far["alarms_received"],
  "near_wire_bytes": near["wire_bytes_sent"], "far_wire_bytes": far["wire_bytes_sent"],
  "bytes_by_class": {k: v["bytes"] for k, v in sent.items()},
  "resent_by_class": {k: v["resent"] for k, v in sent.items()},
  "pending_deltas": near["pending_deltas"], "frames_rejected": far["frames_rejected"],
  "rejected": far["rejected"]}))
sys.exit(0 if equal else 1)
PY
