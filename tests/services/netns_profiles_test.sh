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

tag="pena$$"
ns_a="${tag}a"
ns_b="${tag}b"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  wait 2>/dev/null
  ip netns del "$ns_a" 2>/dev/null
  ip netns del "$ns_b" 2>/dev/null
}
trap cleanup EXIT

ip netns add "$ns_a" 2>/dev/null || skip "cannot create network namespaces here"
ip netns add "$ns_b" || exit 1
ip link add "${tag}va" type veth peer name "${tag}vb" || skip "cannot create a veth pair here"
ip link set "${tag}va" netns "$ns_a"
ip link set "${tag}vb" netns "$ns_b"
ip -n "$ns_a" addr add 10.77.0.1/24 dev "${tag}va"
ip -n "$ns_b" addr add 10.77.0.2/24 dev "${tag}vb"
for pair in "$ns_a ${tag}va" "$ns_b ${tag}vb"; do
  set -- $pair
  ip -n "$1" link set lo up
  ip -n "$1" link set "$2" up
  ip -n "$1" route add 224.0.0.0/4 dev "$2"  # multicast discovery goes over the veth
done

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
run_pair discovery_server pena_ds_server pena_ds_client pena-discovery-server.xml
echo "PASSED: both profiles carry poses between network namespaces"
