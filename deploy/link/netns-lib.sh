# Sourced by the team link scripts (team-link-run.sh): three network namespaces
# building <-> radio <-> post joined by two veth pairs, shaped with tc tbf in the radio
# namespace (the kernel has no netem), with scheduled outages. The namespaces are connected only
# to each other: nothing leaves the machine. Needs root, ip and tc.
# Same link model as run-link.sh (docs/gateway.md, "Link harness"); fixed addresses are fine
# because every run has its own namespaces.
LINK_BUILDING_IP=10.78.1.1
LINK_RADIO_B_IP=10.78.1.2
LINK_RADIO_P_IP=10.78.2.1
LINK_POST_IP=10.78.2.2

# link_setup TAG: creates pl-bld-TAG, pl-radio-TAG, pl-post-TAG and the veth pairs.
link_setup() {
  local tag=$1
  LINK_BLD_NS="pl-bld-$tag"; LINK_RADIO_NS="pl-radio-$tag"; LINK_POST_NS="pl-post-$tag"
  LINK_BLD_IF="lb$tag"; LINK_RB_IF="rb$tag"; LINK_RP_IF="rp$tag"; LINK_POST_IF="lp$tag"
  local ns
  for ns in "$LINK_BLD_NS" "$LINK_RADIO_NS" "$LINK_POST_NS"; do
    ip netns add "$ns"; ip -n "$ns" link set lo up
  done
  ip link add "$LINK_BLD_IF" netns "$LINK_BLD_NS" type veth peer name "$LINK_RB_IF" netns "$LINK_RADIO_NS"
  ip link add "$LINK_POST_IF" netns "$LINK_POST_NS" type veth peer name "$LINK_RP_IF" netns "$LINK_RADIO_NS"
  ip -n "$LINK_BLD_NS" addr add "$LINK_BUILDING_IP/30" dev "$LINK_BLD_IF"
  ip -n "$LINK_RADIO_NS" addr add "$LINK_RADIO_B_IP/30" dev "$LINK_RB_IF"
  ip -n "$LINK_RADIO_NS" addr add "$LINK_RADIO_P_IP/30" dev "$LINK_RP_IF"
  ip -n "$LINK_POST_NS" addr add "$LINK_POST_IP/30" dev "$LINK_POST_IF"
  ip -n "$LINK_BLD_NS" link set "$LINK_BLD_IF" up
  ip -n "$LINK_RADIO_NS" link set "$LINK_RB_IF" up
  ip -n "$LINK_RADIO_NS" link set "$LINK_RP_IF" up
  ip -n "$LINK_POST_NS" link set "$LINK_POST_IF" up
  ip -n "$LINK_BLD_NS" route add default via "$LINK_RADIO_B_IP"
  ip -n "$LINK_POST_NS" route add default via "$LINK_RADIO_P_IP"
  ip netns exec "$LINK_RADIO_NS" sysctl -q -w net.ipv4.ip_forward=1
}

# link_teardown: deletes the namespaces (and with them the veths). Safe to call twice.
link_teardown() {
  local ns
  for ns in "${LINK_BLD_NS:-}" "${LINK_RADIO_NS:-}" "${LINK_POST_NS:-}"; do
    [[ -n $ns ]] && ip netns del "$ns" 2>/dev/null || true
  done
}

# link_shape RATE_KBIT: tbf on both radio egress interfaces. burst holds one full packet;
# peakrate 1 % above the rate makes each packet take its serialisation time as on a radio;
# latency 2 s bounds the modem queue (tail drop beyond it).
link_shape() {
  local rate_bit peak_bit dev
  rate_bit=$(awk "BEGIN{print int($1*1000)}"); peak_bit=$(awk "BEGIN{print int($1*1010)}")
  for dev in "$LINK_RB_IF" "$LINK_RP_IF"; do
    ip netns exec "$LINK_RADIO_NS" tc qdisc replace dev "$dev" root tbf rate "${rate_bit}bit" \
      burst 1600 latency 2s peakrate "${peak_bit}bit" mtu 1600
  done
}

# link_blackhole: a silent radio fade; tbf with a 10-byte burst drops every packet.
link_blackhole() {
  local dev
  for dev in "$LINK_RB_IF" "$LINK_RP_IF"; do
    ip netns exec "$LINK_RADIO_NS" tc qdisc replace dev "$dev" root tbf rate 8bit burst 10 latency 1ms
  done
}

# link_counters FILE: bytes and packets each radio interface sent (toward the post: RP, toward
# the building: RB) and tbf's drop counts, as JSON.
link_counters() {
  {
    echo "{\"links\": $(ip -n "$LINK_RADIO_NS" -s -j link show),"
    echo " \"qdiscs\": $(ip netns exec "$LINK_RADIO_NS" tc -s -j qdisc show),"
    echo " \"to_post_if\": \"$LINK_RP_IF\", \"to_building_if\": \"$LINK_RB_IF\"}"
  } > "$1"
}
