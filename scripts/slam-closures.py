#!/usr/bin/env python3
"""Loop closures of `pena map` judged against a simulated mission's truth (docs/slam.md, "Closures").

For each row of DIR/closures.csv: how far the match's relative pose of its two keyframes lies from
their true relative pose, how far the graph's prediction (the prior) lay from it, and how far the
match moved the new keyframe from that prediction. A closure more than 0.15 m or 1.5 deg from the
truth is called wrong. Prints the wrong ones and a summary by how far each match moved its
keyframe (right closures move little; creeping wrong ones move their keyframe each time).

usage: slam-closures.py DIR/closures.csv TRUTH.tum [--all]
"""
import csv
import math
import sys

from tum_poses import between, read_tum


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    truth = read_tum(sys.argv[2])
    show_all = '--all' in sys.argv[3:]
    bands = [0.1, 0.2, 0.3, math.inf]
    counts = {(w, b): 0 for w in (False, True) for b in bands}
    rows = list(csv.DictReader(open(sys.argv[1])))
    for n, row in enumerate(rows, start=2):
        t0, t1 = round(float(row['older_stamp']), 3), round(float(row['stamp']), 3)
        if t0 not in truth or t1 not in truth:
            sys.exit(f"{sys.argv[1]}:{n}: stamps {t0} / {t1} not in {sys.argv[2]}")
        true = between(truth[t0], truth[t1])
        meas = (float(row['x']), float(row['y']), float(row['theta']))
        prior = (float(row['prior_x']), float(row['prior_y']), float(row['prior_theta']))
        err_m = math.hypot(meas[0] - true[0], meas[1] - true[1])
        err_deg = math.degrees(math.remainder(meas[2] - true[2], 2 * math.pi))
        moved_m = math.hypot(meas[0] - prior[0], meas[1] - prior[1])
        wrong = err_m > 0.15 or abs(err_deg) > 1.5
        counts[(wrong, next(b for b in bands if moved_m < b))] += 1
        if wrong or show_all:
            where = truth[t1]
            print(f"{t0:8.2f} -> {t1:8.2f} s at ({where[0]:5.1f}, {where[1]:5.1f}): off the truth "
                  f"{err_m:.2f} m {err_deg:+.2f} deg, prior off {math.hypot(prior[0] - true[0], prior[1] - true[1]):.2f} m, "
                  f"moved {moved_m:.2f} m, score {row['score']}, window {row['window_m']} m, "
                  f"kept {row['kept']}{'  WRONG' if wrong else ''}")
    kept = sum(1 for r in rows if r['kept'] == '1')
    print(f"{len(rows)} closure matches, {kept} kept; right / wrong by how far the match moved its keyframe:")
    low = 0.0
    for b in bands:
        label = f"{low:.1f}-{b:.1f} m" if b != math.inf else f">= {low:.1f} m"
        print(f"  {label:>10}: {counts[(False, b)]:4d} right, {counts[(True, b)]:4d} wrong")
        low = b


if __name__ == '__main__':
    main()
