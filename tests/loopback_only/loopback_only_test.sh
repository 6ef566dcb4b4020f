#!/usr/bin/env bash
# No PeNa packet leaves the loopback interface: runs pena-fusion and two pena-entity processes
# (loopback profile, deploy/dds/pena-loopback.xml) inside a network namespace that also has a
# "LAN" interface (a veth pair to a second, empty namespace, with the default route and the
# multicast route on it), captures every packet on every interface of that namespace
# (rtps_capture, AF_PACKET), and asserts that no UDP datagram and no RTPS message went over the
# veth while RTPS did flow on lo. A control run first proves the capture sees leaks: dds_ping with
# the LAN profile in the same namespace must put RTPS on the veth. Nothing touches the host's
# interfaces; a broken profile could only reach the empty peer namespace.
#
# Usage: loopback_only_test.sh CAPTURE FUSION ENTITY PENA DDS_PING DEPLOY_DDS_DIR [-- CMD ARGS...]
# With "-- CMD ARGS..." the command (e.g. the demo) replaces the fusion + 2 entities workload; it
# runs in the namespace with a private /dev/shm and FASTRTPS_DEFAULT_PROFILES_FILE set to the
# loopback profile. Exit 0 pass, 1 fail, 77 skipped (not root, no namespaces or AF_PACKET).
set -u
capture_bin=$1 fusion_bin=$2 entity_bin=$3 pena_bin=$4 ping_bin=$5 dds_dir=$6
shift 6
[ "${1:-}" = "--" ] && shift
user_cmd=("$@")
skip() { echo "SKIPPED: $*"; exit 77; }
fail() { echo "FAILED: $*"; exit 1; }
[ "$(id -u)" = 0 ] || skip "needs root to create network namespaces and capture packets"
command -v ip >/dev/null || skip "no ip command (iproute2)"
command -v unshare >/dev/null || skip "no unshare command (util-linux)"

source "$(dirname "$0")/../common/veth_pair.sh"
tag="plo$$"
ns="${tag}a" peer="${tag}b"
work=$(mktemp -d -t pena-loopback-only.XXXXXX)
capture_pid=""
cleanup() {
  [ -n "$capture_pid" ] && kill "$capture_pid" 2>/dev/null
  wait 2>/dev/null
  veth_pair_teardown "$ns" "$peer"
  rm -rf "$work"
}
trap cleanup EXIT

veth_pair_setup "$ns" "$peer" "${tag}x" "${tag}y" 10.78.0.1 10.78.0.2
ip -n "$ns" route add default via 10.78.0.2
export FASTRTPS_DEFAULT_PROFILES_FILE="$dds_dir/pena-loopback.xml"

# Runs "$@" in the namespace with a private /dev/shm (shared by everything "$@" starts).
in_ns() { ip netns exec "$ns" unshare --mount sh -c 'mount -t tmpfs tmpfs /dev/shm && exec "$@"' sh "$@"; }

start_capture() {  # output file
  ip netns exec "$ns" "$capture_bin" > "$1" 2>&1 &
  capture_pid=$!
  for _ in $(seq 100); do grep -q ready "$1" 2>/dev/null && return 0; sleep 0.05; done
  grep -q "AF_PACKET" "$1" && skip "$(cat "$1")"
  fail "rtps_capture did not start: $(cat "$1")"
}
stop_capture() {  # the capture prints its counts when interrupted
  kill -INT "$capture_pid"; wait "$capture_pid"; capture_pid=""
}
value() {  # the number after word $2 in file $1
  sed -n "s/.*\b$2 \([0-9]*\).*/\1/p" "$1" | tail -1; }

# 1. Control: the LAN profile must be seen on the veth, or the capture proves nothing.
start_capture "$work/control.txt"
in_ns "$ping_bin" --role pub --profile pena_lan --profiles-file "$dds_dir/pena-lan.xml" \
  --profiles-file "$dds_dir/pena-qos.xml" --domain 9 --id control --seconds 6 >/dev/null 2>&1
stop_capture
cat "$work/control.txt"
[ "$(value "$work/control.txt" non_loopback_rtps)" -gt 0 ] ||
  fail "control: the LAN profile's RTPS was not seen on the veth; the capture is blind"
echo "ok: control (pena_lan) put $(value "$work/control.txt" non_loopback_rtps) RTPS messages on the veth"

# 2. The workload on the loopback profile.
if [ ${#user_cmd[@]} -eq 0 ]; then
  cat > "$work/two_robots.scn" <<'SCN'
pena-scenario 1
name loopback_only
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity robot1 robot 2 2 0 speed=0.8
waypoint robot1 22 2
entity robot2 robot 22 3 3.14159 speed=0.8
waypoint robot2 2 3
SCN
  "$pena_bin" simulate --scenario "$work/two_robots.scn" --seed 1 --out "$work/mission" >/dev/null ||
    fail "pena simulate failed"
  cat > "$work/workload.sh" <<WORK
profiles="--profiles-file $dds_dir/pena-loopback.xml --profiles-file $dds_dir/pena-qos.xml --domain 9"
"$fusion_bin" --state-dir "$work/state" --out "$work/fusion_out" \$profiles --log-level warn &
fusion=\$!
rc=0
for e in robot1 robot2; do
  "$entity_bin" --input "$work/mission/\$e" --rate 4 --out "$work/\$e" \$profiles \
    --wait-for-readers 20 --linger 5 --log-level warn &
done
for job in \$(jobs -p); do [ "\$job" = "\$fusion" ] || wait "\$job" || rc=1; done
kill -INT \$fusion; wait \$fusion || rc=1
exit \$rc
WORK
  user_cmd=(bash "$work/workload.sh")
fi
start_capture "$work/run.txt"
in_ns "${user_cmd[@]}" > "$work/workload.log" 2>&1
rc=$?
stop_capture
cat "$work/run.txt"
[ "$rc" -eq 0 ] || fail "the workload exited $rc: $(tail -20 "$work/workload.log")"
if [ -f "$work/fusion_out/global_map.csv" ]; then
  rows=$(($(wc -l < "$work/fusion_out/global_map.csv") - 1))
  [ "$rows" -gt 0 ] || fail "fusion's global map is empty: the entities' data did not arrive"
  echo "ok: fusion merged $rows segments from robot1 and robot2"
fi
[ "$(value "$work/run.txt" loopback_rtps)" -gt 0 ] || fail "no RTPS on lo: nothing was captured"
[ "$(value "$work/run.txt" non_loopback_rtps)" -eq 0 ] || fail "RTPS messages left the loopback interface"
[ "$(value "$work/run.txt" non_loopback_udp)" -eq 0 ] || fail "UDP datagrams left the loopback interface"
echo "PASSED: $(value "$work/run.txt" loopback_rtps) RTPS messages on lo, none on any other interface"
