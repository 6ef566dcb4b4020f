#!/usr/bin/env python3
"""Error budget of `pena localise` on simulated missions (docs/localisation.md, "Figures").

Per scan of each run, the error against truth.tum, counted as `pena localise` counts its in-map
RMS (true pose inside the plan's bounding box, the first 5 m walked after each re-entry left out),
split by where the entity is (corridor y 13-15, archive x 28-34 north of it, other rooms), by the
last plan round before the scan (status.csv: status, accepted, degenerate), by the time since the
last accepted round and by 4 m bands of x; x is along the office corridor, y across it. Then the
episodes (at least 4 scans in a row more than 0.2 m off) that carry most of the squared error.

usage: localise-error-budget.py PLAN.csv RUN_DIR TRUTH.tum [RUN_DIR TRUTH.tum ...]
RUN_DIR: a `pena localise --out` directory (trajectory.tum, status.csv), or a `pena odometry --out`
directory (trajectory.tum only: the odometry alone, on the same metric).
"""
import collections
import csv
import math
import os
import sys

from tum_poses import read_tum


def plan_box(path):
    xs, ys = [], []
    for row in csv.DictReader(open(path)):
        xs += [float(row['x1']), float(row['x2'])]
        ys += [float(row['y1']), float(row['y2'])]
    return min(xs), max(xs), min(ys), max(ys)


def region(x, y):
    if 13 <= y <= 15:
        return 'corridor'
    if y > 15 and 28 <= x <= 34:
        return 'archive'
    return 'north rooms' if y > 15 else 'south rooms, passage'


def angle(a):
    return math.atan2(math.sin(a), math.cos(a))


def scans(run_dir, truth_path, box):
    est, truth = read_tum(os.path.join(run_dir, 'trajectory.tum')), read_tum(truth_path)
    rounds = {}
    status_path = os.path.join(run_dir, 'status.csv')
    if os.path.exists(status_path):
        rounds = {round(float(r['stamp']), 3): r for r in csv.DictReader(open(status_path))}
    rows, was_in, since_entry_m, last, last_round, last_accepted = [], True, 1e9, None, None, None
    for t in sorted(est):
        if t not in truth:
            continue
        tx, ty, tth = truth[t]
        if last:
            since_entry_m += math.hypot(tx - last[0], ty - last[1])
        last = (tx, ty)
        inside = box[0] <= tx <= box[1] and box[2] <= ty <= box[3]
        if inside and not was_in:
            since_entry_m = 0.0
        was_in = inside
        if t in rounds:
            last_round = rounds[t]
            if last_round['accepted'] == '1':
                last_accepted = t
        if not inside or since_entry_m < 5.0:
            continue
        ex, ey, eth = est[t]
        rows.append({'run': run_dir, 't': t, 'x': tx, 'y': ty, 'dx': ex - tx, 'dy': ey - ty,
                     'dh': math.degrees(angle(eth - tth)), 'region': region(tx, ty),
                     'round': '-' if last_round is None else '%s %s %s' % (
                         last_round['status'], 'accepted' if last_round['accepted'] == '1' else 'rejected',
                         'degenerate' if last_round['degenerate'] == '1' else 'full'),
                     'age': None if last_accepted is None else t - last_accepted})
    return rows


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else 0.0


def table(title, rows, key, total):
    print(title)
    groups = collections.defaultdict(list)
    for r in rows:
        groups[key(r)].append(r)
    for k in sorted(groups):
        g = groups[k]
        sq = sum(r['dx'] ** 2 + r['dy'] ** 2 for r in g)
        print('  %-34s %5d scans  %5.1f %% of squared error  RMS %.3f m (x %.3f, y %.3f)' % (
            k, len(g), 100 * sq / total, math.sqrt(sq / len(g)), rms([r['dx'] for r in g]),
            rms([r['dy'] for r in g])))


def age_band(age):
    if age is None:
        return 'no accepted round yet'
    return next(label for limit, label in ((0, '0: at the round'), (1, '1: <= 1 s'), (3, '2: <= 3 s'),
                                           (10, '3: <= 10 s'), (1e18, '4: > 10 s')) if age <= limit)


def episodes(rows, total, count=12):
    found, current = [], []
    for r in rows + [None]:
        if r and math.hypot(r['dx'], r['dy']) > 0.2 and (not current or (
                r['run'] == current[-1]['run'] and r['t'] - current[-1]['t'] <= 1.01)):
            current.append(r)
            continue
        if len(current) >= 4:
            found.append(current)
        current = [r] if r and math.hypot(r['dx'], r['dy']) > 0.2 else []
    found.sort(key=lambda e: -sum(r['dx'] ** 2 + r['dy'] ** 2 for r in e))
    print('episodes (>= 4 scans in a row over 0.2 m), largest first:')
    for e in found[:count]:
        sq = sum(r['dx'] ** 2 + r['dy'] ** 2 for r in e)
        print('  %s %.2f-%.2f s, %d scans, %4.1f %%: (%.1f, %.1f) -> (%.1f, %.1f), mean error (%+.2f, %+.2f) m, %s' % (
            e[0]['run'], e[0]['t'], e[-1]['t'], len(e), 100 * sq / total, e[0]['x'], e[0]['y'], e[-1]['x'],
            e[-1]['y'], sum(r['dx'] for r in e) / len(e), sum(r['dy'] for r in e) / len(e), e[0]['region']))


def main(argv):
    if len(argv) < 4 or len(argv) % 2:
        sys.exit(__doc__)
    box = plan_box(argv[1])
    rows = []
    for run_dir, truth_path in zip(argv[2::2], argv[3::2]):
        mine = scans(run_dir, truth_path, box)
        print('%s: in-map RMS %.3f m, heading %.2f deg (%d scans)' % (
            run_dir, rms([math.hypot(r['dx'], r['dy']) for r in mine]), rms([r['dh'] for r in mine]), len(mine)))
        rows += mine
    total = sum(r['dx'] ** 2 + r['dy'] ** 2 for r in rows)
    print('all: %d scans, RMS %.3f m (x %.3f, y %.3f), heading %.2f deg' % (
        len(rows), math.sqrt(total / len(rows)), rms([r['dx'] for r in rows]), rms([r['dy'] for r in rows]),
        rms([r['dh'] for r in rows])))
    table('by region:', rows, lambda r: r['region'], total)
    table('by the last plan round:', rows, lambda r: r['round'], total)
    table('by time since the last accepted round:', rows, lambda r: age_band(r['age']), total)
    table('by x (4 m bands):', rows, lambda r: 'x %02d-%02d m' % (4 * (r['x'] // 4), 4 * (r['x'] // 4) + 4), total)
    episodes(rows, total)


if __name__ == '__main__':
    main(sys.argv)
