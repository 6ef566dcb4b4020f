#!/usr/bin/env python3
"""How the command post's global map follows fusion across the outage of one team-link run
(docs/link-experiments.md, "Findings"): the first post map change after the link returned, when
the post caught up with fusion, and the lag of fusion's versions before, during and after it.

usage: map-resume.py RUN_DIR   (a team-link-run.sh output: outage-*-ns, post/map.csv,
                                fusion/global_versions.csv)
"""
import csv
import statistics
import sys

run = sys.argv[1]
end = int(open(run + "/outage-end-ns").read())
start = int(open(run + "/outage-start-ns").read())
post = [(int(r["recv_ns"]), int(r["version"])) for r in csv.DictReader(open(run + "/post/map.csv"))]
fusion = []  # (wall ns published, version)
for row in csv.reader(open(run + "/fusion/global_versions.csv")):
    try:
        fusion.append((int(row[2]), int(row[1])))
    except (ValueError, IndexError):
        pass  # header
after = [t for t, _ in post if t > end]
print("outage %.1f s; first post map change %.1f s after the link returned"
      % ((end - start) / 1e9, (after[0] - end) / 1e9 if after else float("nan")))
lags = []  # (published, s after the outage began; lag until the post held it)
for t, v in fusion:
    held = next((pt for pt, pv in post if pv >= v and pt >= t), None)
    if held is not None:
        lags.append(((t - start) / 1e9, (held - t) / 1e9))
outage_s = (end - start) / 1e9
for lo, hi, name in [(-1e9, 0, "before outage"), (0, outage_s, "during"), (outage_s, 1e9, "after")]:
    sel = [lag for at, lag in lags if lo <= at < hi]
    if sel:
        print("%s: %d versions, lag median %.1f s max %.1f s" % (name, len(sel), statistics.median(sel), max(sel)))
for pt, pv in post:
    if pt <= end:
        continue
    if pv >= max([v for t, v in fusion if t <= pt] or [0]):
        print("post caught up with fusion %.1f s after the link returned" % ((pt - end) / 1e9))
        break
