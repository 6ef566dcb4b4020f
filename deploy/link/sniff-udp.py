#!/usr/bin/env python3
"""UDP bytes per (interface, source, destination) sent on every interface of the current network
namespace during N seconds (no tcpdump on this machine). Run inside a link experiment's radio
namespace: ip netns exec pl-radio-TAG python3 deploy/link/sniff-udp.py 10
Fast DDS ports: 7400 + 250 * domain + 10 + 2 * participant = metatraffic (discovery, EDP,
liveliness), + 11 + 2 * participant = user data."""
import socket, struct, sys, time, collections
s = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.ntohs(0x0003))
s.settimeout(0.5)
end = time.time() + float(sys.argv[1]); count = collections.Counter(); pk = collections.Counter()
while time.time() < end:
    try:
        data, addr = s.recvfrom(65535)
    except socket.timeout:
        continue
    if addr[2] != socket.PACKET_OUTGOING:  # count each forwarded packet once: as sent
        continue
    if len(data) < 42 or data[12:14] != b"\x08\x00" or data[23] != 17:
        continue
    ihl = (data[14] & 15) * 4
    src = socket.inet_ntoa(data[26:30]); dst = socket.inet_ntoa(data[30:34])
    sp, dp = struct.unpack("!HH", data[14 + ihl:18 + ihl])
    key = f"{addr[0]} {src}:{sp} -> {dst}:{dp}"
    count[key] += len(data); pk[key] += 1
for key, b in count.most_common(15):
    print(f"{b:9d} B {pk[key]:6d} pkts  {key}")
