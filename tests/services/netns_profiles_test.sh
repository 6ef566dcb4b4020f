#!/usr/bin/env bash
# The LAN and discovery-server profiles (deploy/dds/pena-lan.xml, pena-discovery-server.xml)
# between two network namespaces joined by a veth pair (10.77.0.1 <-> 10.77.0.2): a publisher in
# one, a subscriber in the other, each with its own /dev/shm so shared memory cannot carry the
# data. Nothing touches the host's interfaces. Creates and removes everything itself.
# Usage: netns_profiles_test.sh DDS_PING DEPLOY_DDS_DIR. Exit 77 (skipped) without root/netns.
set -u
ping_bin=$1
dds_dir=$2
skip() { echo "SKIPPED: $*"; exit 77; }
[ "$(id -u)" = 0 ] || skip "needs root to create network namespaces"
command -v ip >/dev/null || skip "no ip command (iproute2)"
command -v unshare >/dev/null || skip "no unshare command (util-linux)"

source "$(dirname "$0")/../common/veth_pair.sh"
tag="pena$$"
ns_a="${tag}a"
ns_b="${tag}b"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  wait 2>/dev/null
  veth_pair_teardown "$ns_a" "$ns_b"
}
trap cleanup EXIT

veth_pair_setup "$ns_a" "$ns_b" "${tag}va" "${tag}vb" 10.77.0.1 10.77.0.2

# Prefix that runs dds_ping in a namespace with a private /dev/shm (every step execs, so $! of
# a backgrounded run is dds_ping itself).
private_shm=(unshare --mount sh -c 'mount -t tmpfs tmpfs /dev/shm && exec "$@"' sh "$ping_bin")

run_pair() {  # name pub_profile sub_profile profile_file
  local name=$1 pub_profile=$2 sub_profile=$3 file=$4
  ip netns exec "$ns_a" "${private_shm[@]}" --role pub --profile "$pub_profile" --profiles-file "$dds_dir/$file" \
    --profiles-file "$dds_dir/pena-qos.xml" --domain 7 --id "$name" --seconds 25 &
  local pub=$!
  pids+=("$pub")
  ip netns exec "$ns_b" "${private_shm[@]}" --role sub --profile "$sub_profile" --profiles-file "$dds_dir/$file" \
    --profiles-file "$dds_dir/pena-qos.xml" --domain 7 --count 20 --seconds 20
  local rc=$?
  kill "$pub" 2>/dev/null
  wait "$pub" 2>/dev/null
  if [ "$rc" -ne 0 ]; then
    echo "FAILED: $name: the subscriber in $ns_b did not receive 20 poses from $ns_a"
    exit 1
  fi
  echo "ok: $name ($pub_profile -> $sub_profile across the veth pair)"
}

run_pair lan pena_lan pena_lan pena-lan.xml
# The central fusion's LAN profile (no shared memory) against an entity's pena_lan, both ways.
run_pair lan_udp_pub pena_lan_udp pena_lan pena-lan.xml
run_pair lan_udp_sub pena_lan pena_lan_udp pena-lan.xml
run_pair discovery_server pena_ds_server pena_ds_client pena-discovery-server.xml
echo "PASSED: the LAN profiles and the discovery server carry poses between network namespaces"
