# Sourced by the network-namespace tests (loopback_only_test.sh, netns_profiles_test.sh): two
# fresh namespaces joined by one veth pair, nothing else. Only those namespaces see the pair;
# the host's interfaces are never touched. IPv6 is off (PeNa's transports are UDPv4 and shared
# memory) so the kernel's own router solicitations do not show up in packet captures.
# Needs root and ip; the caller has checked both and defined skip() (exit 77).

# veth_pair_setup NS_A NS_B IF_A IF_B IP_A IP_B: namespaces NS_A and NS_B, IF_A (IP_A/24) in NS_A
# joined to IF_B (IP_B/24) in NS_B, both up with lo, and the multicast route on the veth on both
# sides so that multicast discovery, when a profile uses it, goes over the pair.
# Skips the test when namespaces or veth pairs cannot be made here.
veth_pair_setup() {
  local ns_a=$1 ns_b=$2 if_a=$3 if_b=$4 ip_a=$5 ip_b=$6
  ip netns add "$ns_a" 2>/dev/null || skip "cannot create network namespaces here"
  ip netns add "$ns_b" || exit 1
  ip link add "$if_a" type veth peer name "$if_b" || skip "cannot create a veth pair here"
  ip link set "$if_a" netns "$ns_a"
  ip link set "$if_b" netns "$ns_b"
  ip -n "$ns_a" addr add "$ip_a/24" dev "$if_a"
  ip -n "$ns_b" addr add "$ip_b/24" dev "$if_b"
  local ns dev
  for ns in "$ns_a" "$ns_b"; do
    [ "$ns" = "$ns_a" ] && dev=$if_a || dev=$if_b
    ip netns exec "$ns" sysctl -qw net.ipv6.conf.all.disable_ipv6=1 2>/dev/null
    ip -n "$ns" link set lo up
    ip -n "$ns" link set "$dev" up
    ip -n "$ns" route add 224.0.0.0/4 dev "$dev"
  done
}

# veth_pair_teardown NS...: deletes the namespaces (and with them the pair). Safe to call twice.
veth_pair_teardown() {
  local ns
  for ns in "$@"; do ip netns del "$ns" 2>/dev/null; done
  return 0
}
