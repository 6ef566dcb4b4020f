#!/usr/bin/env python3
"""Figures of one team link run (team-link-run.sh OUT): prints result.json, writes the time
series OUT/series-age.csv and OUT/series-map.csv for the plots.

usage: analyse-run.py OUT PENA_MONITOR

Pose age at the post = the post monitor's take time minus the pose's source timestamp, which is
the entity's write time in both modes (every namespace shares the system clock). Map convergence = first time the post's map digest equals fusion's final map's
digest, minus the time the building monitor saw the final version published (the last change).
"""
import csv
import glob
import json
import os
import subprocess
import sys

out, monitor = sys.argv[1], sys.argv[2]


def load_csv(path):
    try:
        with open(path) as f:
            return list(csv.DictReader(f))
    except OSError:
        return []


def pct(values, q):
    if not values:
        return None
    values = sorted(values)
    return values[min(len(values) - 1, int(q * (len(values) - 1) + 0.5))]


def rnd(x, n=3):
    return None if x is None else round(x, n)


run = json.load(open(f"{out}/run.json"))
times = json.load(open(f"{out}/times.json"))
t0 = times["entities_start_ns"]
outage = None
if os.path.exists(f"{out}/outage-start-ns") and os.path.exists(f"{out}/outage-end-ns"):
    outage = ((int(open(f"{out}/outage-start-ns").read()) - t0) * 1e-9,
              (int(open(f"{out}/outage-end-ns").read()) - t0) * 1e-9)

# Poses. The age is the post's receive time minus the pose's source timestamp: plain DDS keeps
# the entity's, and the far gateway republishes each pose with the original write time
# (StampedWriter), so both are the entity's write time. Checked: the fraction of post poses whose
# (entity, source ms) matches a pose the building monitor saw written.
written = set()
for row in load_csv(f"{out}/building/poses.csv"):
    written.add((row["entity"], int(row["source_ns"]) // 1000000))
ages, series_age, seen, by_entity, matched = [], [], set(), {}, 0
for row in load_csv(f"{out}/post/poses.csv"):
    key = (row["entity"], int(row["source_ns"]) // 1000000)
    if key in seen:
        continue
    seen.add(key)
    matched += (key in written) or ((key[0], key[1] - 1) in written) or ((key[0], key[1] + 1) in written)
    recv = int(row["recv_ns"])
    age = (recv - int(row["source_ns"])) * 1e-9
    ages.append(age)
    series_age.append(((recv - t0) * 1e-9, age, row["entity"]))
    by_entity.setdefault(row["entity"], []).append(recv)
# Poses written = the poses each entity published (its trajectory.tum, one line per pose).
poses_written = 0
for path in glob.glob(f"{out}/entities/*/trajectory.tum"):
    poses_written += sum(1 for line in open(path) if line.strip() and not line.startswith("#"))
gaps = [max(((b - a) * 1e-9 for a, b in zip(sorted(v), sorted(v)[1:])), default=0.0)
        for v in by_entity.values()]
with open(f"{out}/series-age.csv", "w") as f:
    f.write("t_s,age_s,entity\n")
    for t, age, entity in series_age:
        f.write(f"{t:.3f},{age:.4f},{entity}\n")

# Map.
def digest_of(path):
    if not os.path.exists(path):
        return None
    result = subprocess.run([monitor, "--digest", path], capture_output=True, text=True)
    return result.stdout.split()[0] if result.returncode == 0 else None


# The reference: fusion's own record of every global version it published (from,to,wall ns)
# and its final map; the building monitor's view is kept as a cross-check.
fusion_digest = digest_of(f"{out}/fusion/global_map.csv")
published = []
try:
    for line in open(f"{out}/fusion/global_versions.csv"):
        fields = line.strip().split(",")
        if len(fields) == 3 and fields[0].isdigit():
            published.append((int(fields[1]), int(fields[2])))
except OSError:
    pass
bld_rows = load_csv(f"{out}/building/map.csv")
post_rows = load_csv(f"{out}/post/map.csv")
final = fusion_digest
final_version = published[-1][0] if published else 0
last_change_ns = published[-1][1] if published else None
post_equal_ns = None
for row in post_rows:
    if row["digest"] == final and post_equal_ns is None:
        post_equal_ns = int(row["recv_ns"])
    elif row["digest"] != final:
        post_equal_ns = None
converged_s = None
if post_equal_ns is not None and last_change_ns is not None:
    converged_s = (post_equal_ns - last_change_ns) * 1e-9
bld_versions = {v for v, _ns in published}
post_versions = {int(r["to_version"]) for r in post_rows if r["kind"] == "delta" and r["status"] == "applied"}
post_snapshots = sum(1 for r in post_rows if r["kind"] == "snapshot" and r["status"] == "applied")
with open(f"{out}/series-map.csv", "w") as f:
    f.write("t_s,side,version,segments,fraction\n")
    for v, ns in published:
        f.write(f"{(ns - t0) * 1e-9:.3f},fusion,{v},0,{v / final_version:.4f}\n")
    for side, rows in (("post", post_rows),):
        for r in rows:
            frac = int(r["version"]) / final_version if final_version else 0.0
            f.write(f"{(int(r['recv_ns']) - t0) * 1e-9:.3f},{side},{r['version']},{r['segments']},{frac:.4f}\n")

# Bytes on the link.
link = {}
try:
    counters = json.load(open(f"{out}/link-counters.json"))
    for entry in counters["links"]:
        stats = entry.get("stats64", entry.get("stats", {}))
        # The radio's interface toward the post transmits what reached the post and receives what
        # the post offered; likewise toward the building.
        if entry["ifname"] == counters["to_post_if"]:
            link["to_post_bytes"] = stats["tx"]["bytes"]; link["to_post_packets"] = stats["tx"]["packets"]
            link["offered_by_post_bytes"] = stats["rx"]["bytes"]
        if entry["ifname"] == counters["to_building_if"]:
            link["to_building_bytes"] = stats["tx"]["bytes"]; link["to_building_packets"] = stats["tx"]["packets"]
            link["offered_by_building_bytes"] = stats["rx"]["bytes"]
    for q in counters["qdiscs"]:
        # tbf counters since the last (re)shaping, i.e. since the outage ended.
        if q.get("dev") == counters["to_post_if"]:
            link["tbf_drops_to_post_after_outage"] = q.get("drops")
        if q.get("dev") == counters["to_building_if"]:
            link["tbf_drops_to_building_after_outage"] = q.get("drops")
except (OSError, ValueError, KeyError):
    pass
duration_s = (times["end_ns"] - times["entities_start_ns"]) * 1e-9
post_monitor = {}
try:
    post_monitor = json.load(open(f"{out}/post/monitor.json"))
except (OSError, ValueError):
    pass
gateway = {}
for side in ("building", "post"):
    try:
        gateway[side] = json.load(open(f"{out}/gateway/{side}.json"))
    except (OSError, ValueError):
        pass
bytes_by_class = {}
if "building" in gateway and isinstance(gateway["building"].get("sent"), dict):
    bytes_by_class = {k: v.get("bytes") for k, v in gateway["building"]["sent"].items()
                      if isinstance(v, dict)}
elif post_monitor:
    bytes_by_class = {"payload " + k: v for k, v in post_monitor.get("bytes_by_topic", {}).items()}

outside = [a for (t, a, _e) in series_age
           if outage is None or not (outage[0] <= t <= outage[1] + 5.0)]
result = {
    **{k: run[k] for k in ("mode", "rate_kbit", "entity_rate", "outage", "delay_s", "loss")},
    "outage_measured_s": [rnd(outage[0], 1), rnd(outage[1], 1)] if outage else None,
    "duration_s": rnd(duration_s, 1),
    "poses_written": poses_written, "poses_at_post": len(seen),
    "post_pose_stamps_matching_building": rnd(matched / len(seen) if seen else None),
    "pose_delivery": rnd(len(seen) / poses_written if poses_written else None),
    "pose_age_p50_s": rnd(pct(ages, 0.5)), "pose_age_p99_s": rnd(pct(ages, 0.99)),
    "pose_age_max_s": rnd(max(ages) if ages else None),
    "pose_age_p99_outside_outage_s": rnd(pct(outside, 0.99)),
    "longest_pose_gap_s": rnd(max(gaps) if gaps else None, 1),
    "map_final_version": final_version,
    "building_monitor_map_equals_fusion": bool(bld_rows) and bld_rows[-1]["digest"] == fusion_digest,
    "post_map_equals_fusion": bool(post_rows) and fusion_digest is not None and post_rows[-1]["digest"] == fusion_digest,
    "map_converged_after_last_change_s": rnd(converged_s, 2),
    "last_map_change_s": rnd((last_change_ns - t0) * 1e-9 if last_change_ns else None, 1),
    "map_versions_published": len(bld_versions),
    "map_versions_by_delta_at_post": len(post_versions & bld_versions),
    "map_deltas_missing_at_post": len(bld_versions - post_versions),
    "post_snapshots_used": post_snapshots,
    "post_deltas_pending": post_monitor.get("deltas_pending"),
    "link": link,
    "link_to_post_bit_s": rnd(link.get("to_post_bytes", 0) * 8 / duration_s if duration_s > 0 else None, 0),
    "bytes_by_class": bytes_by_class,
    "link_sealed": gateway.get("building", {}).get("sealed"),
    "seal_bytes_to_post": gateway.get("building", {}).get("seal_bytes_sent"),
}
print(json.dumps(result))
