#!/usr/bin/env python3
"""Writes a copy of deploy/dds/pena-qos.xml whose writers that cross the link are rate-limited by
Fast DDS flow controllers (plain-DDS baseline of docs/link-experiments.md).

Fast DDS 2.9.1 (the installed library) parses flow controllers in XML only as the older
<throughputController><bytesPerPeriod/><periodMillisecs/></throughputController> element of a
data_writer (it becomes that writer's flow controller); <flow_controller_descriptor_list> and
<flow_controller_name> are not in its XML parser (checked with `strings libfastrtps.so.2.9.1`).
A throughput controller needs ASYNCHRONOUS publishMode.

usage: flow-qos.py RATE_KBIT ENTITIES IN_QOS_XML OUT_QOS_XML
The link budget (90 % of the rate, as the gateway uses) is shared: poses 50 % split over the
entities, global-map deltas 40 %, global-map snapshots 10 %. The period is long enough that one
period holds at least 400 bytes (a pose sample and its RTPS headers), at least 100 ms.
"""
import math
import re
import sys

rate_kbit, entities, src, dst = float(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
budget_bit_s = rate_kbit * 1000 * 0.9
shares = {
    "pena_pose_writer": 0.5 / entities,
    "pena_global_map_delta_writer": 0.4,
    "pena_global_map_snapshot_writer": 0.1,
}
text = open(src).read()
for profile, share in shares.items():
    bits = budget_bit_s * share
    period_ms = max(100, math.ceil(400 * 8 * 1000 / bits))
    per_period = max(1, int(bits * period_ms / 1000 / 8))
    pattern = re.compile(r'(<data_writer profile_name="%s">.*?)(</qos>)(.*?)(</data_writer>)' % profile,
                         re.S)
    insert_qos = "  <publishMode><kind>ASYNCHRONOUS</kind></publishMode>\n    "
    insert_writer = ("  <throughputController><bytesPerPeriod>%d</bytesPerPeriod>"
                     "<periodMillisecs>%d</periodMillisecs></throughputController>\n  "
                     % (per_period, period_ms))
    text, count = pattern.subn(lambda m: m.group(1) + insert_qos + m.group(2) + m.group(3)
                               + insert_writer + m.group(4), text, count=1)
    if count != 1:
        sys.exit("flow-qos.py: %s: no data_writer profile %s" % (src, profile))
open(dst, "w").write(text)
