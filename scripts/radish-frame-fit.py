#!/usr/bin/env python3
"""Frame of a radish-corrected log against a Freiburg log of the same run (docs/localisation.md,
"Real data").

The two logs' clocks differ (intel: corrected = Freiburg - first stamp, aces: - 70.1797 s, csail:
rounded stamps), so scans are paired by identical ranges (2 decimals). The rigid transform
corrected_from_trajectory is then fitted (least squares, positions) between the corrected poses and
a TUM trajectory of the Freiburg log (e.g. `pena odometry`'s) at the paired stamps.

usage: radish-frame-fit.py CORRECTED.log.gz FREIBURG.clf.gz TRAJECTORY.tum [SECONDS]
SECONDS: use only pairs within the first SECONDS of the trajectory (default: all), so that
odometry drift does not enter the fit. Prints the transform, the start pose of the trajectory in
the corrected frame and the residuals.
"""
import bisect
import gzip
import math
import sys


def scans(path):
    opener = gzip.open if path.endswith('.gz') else open
    with opener(path, 'rt') as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields or fields[0] != 'FLASER':
                continue
            try:
                n = int(fields[1])
                rest = fields[2 + n:]
                yield (tuple(round(float(r), 2) for r in fields[2:2 + n]), float(rest[6]),
                       tuple(float(v) for v in rest[0:3]))
            except (ValueError, IndexError):
                sys.exit('%s:%d: malformed FLASER line' % (path, number))


def read_tum(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith('#') or not line.strip():
                continue
            v = [float(x) for x in line.split()]
            out.append((v[0], v[1], v[2], 2.0 * math.atan2(v[6], v[7])))
    return out


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    corrected, freiburg, trajectory = sys.argv[1:4]
    seconds = float(sys.argv[4]) if len(sys.argv) > 4 else math.inf
    stamp_of = {}
    for key, stamp, _ in scans(freiburg):
        stamp_of.setdefault(key, stamp)
    traj = read_tum(trajectory)
    if not traj:
        sys.exit(trajectory + ': no poses')
    stamps = [p[0] for p in traj]
    pairs, unpaired = [], 0
    for key, _, pose in scans(corrected):
        stamp = stamp_of.get(key)
        if stamp is None:
            unpaired += 1
            continue
        if stamp - stamps[0] > seconds:
            continue
        i = bisect.bisect_left(stamps, stamp - 1e-3)
        if i < len(traj) and abs(stamps[i] - stamp) <= 1e-3:
            pairs.append((pose, traj[i][1:]))
    if len(pairs) < 3:
        sys.exit('only %d scan pairs (%d corrected scans unpaired)' % (len(pairs), unpaired))
    n = len(pairs)
    ca = [sum(a[k] for a, _ in pairs) / n for k in (0, 1)]
    cb = [sum(b[k] for _, b in pairs) / n for k in (0, 1)]
    c = s = 0.0
    for a, b in pairs:
        ax, ay, bx, by = a[0] - ca[0], a[1] - ca[1], b[0] - cb[0], b[1] - cb[1]
        c += bx * ax + by * ay
        s += bx * ay - by * ax
    th = math.atan2(s, c)
    cos, sin = math.cos(th), math.sin(th)
    tx = ca[0] - (cos * cb[0] - sin * cb[1])
    ty = ca[1] - (sin * cb[0] + cos * cb[1])
    err, herr = [], []
    for a, b in pairs:
        err.append(math.hypot(cos * b[0] - sin * b[1] + tx - a[0], sin * b[0] + cos * b[1] + ty - a[1]))
        herr.append(math.degrees((b[2] + th - a[2] + math.pi) % (2 * math.pi) - math.pi))
    x0, y0, h0 = traj[0][1:]
    print('%d scan pairs (%d corrected scans unpaired)' % (n, unpaired))
    print('corrected_from_trajectory: x %.3f m, y %.3f m, theta %.2f deg' % (tx, ty, math.degrees(th)))
    print('trajectory start in the corrected frame: %.3f,%.3f,%.2f' %
          (cos * x0 - sin * y0 + tx, sin * x0 + cos * y0 + ty,
           math.degrees((h0 + th + math.pi) % (2 * math.pi) - math.pi)))
    print('residual: position RMS %.3f m (max %.3f m), heading RMS %.2f deg' %
          (math.sqrt(sum(e * e for e in err) / n), max(err), math.sqrt(sum(e * e for e in herr) / n)))


if __name__ == '__main__':
    main()
