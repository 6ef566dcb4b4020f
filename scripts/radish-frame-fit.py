#!/usr/bin/env python3
"""Frame of a radish-corrected log against a Freiburg log of the same run (docs/localisation.md,
"Real data").

The two logs' clocks differ (intel: corrected = Freiburg - first stamp, aces: - 70.1797 s, csail:
rounded stamps), so scans are paired by identical ranges (2 decimals). The rigid transform
corrected_from_trajectory is then fitted (least squares, positions) between the corrected poses and
a TUM trajectory of the Freiburg log (e.g. `pena odometry`'s) at the paired stamps.

usage: radish-frame-fit.py CORRECTED.log.gz FREIBURG.clf.gz TRAJECTORY.tum [SECONDS] [--tum OUT]
SECONDS: use only pairs within the first SECONDS of the trajectory (default: all), so that
odometry drift does not enter the fit. Prints the transform, the start pose of the trajectory in
the corrected frame and the residuals.
--tum OUT: also write every paired corrected pose, moved into the trajectory's frame by the
fitted transform, at its Freiburg stamp: ground truth for the trajectory (SLAM-corrected, so good
to a few centimetres), e.g. for scripts/covariance-consistency.py.
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


def fit_rigid(pairs):
    """The rigid transform (theta, tx, ty) taking the b positions onto the a positions, least
    squares over [(a, b)] (positions first in each)."""
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
    return th, ca[0] - (cos * cb[0] - sin * cb[1]), ca[1] - (sin * cb[0] + cos * cb[1])


def main():
    args = sys.argv[1:]
    tum_out = None
    if '--tum' in args:
        i = args.index('--tum')
        if i + 1 >= len(args):
            sys.exit(__doc__)
        tum_out = args[i + 1]
        del args[i:i + 2]
    if len(args) < 3:
        sys.exit(__doc__)
    corrected, freiburg, trajectory = args[0:3]
    seconds = float(args[3]) if len(args) > 3 else math.inf
    stamp_of = {}
    for key, stamp, _ in scans(freiburg):
        stamp_of.setdefault(key, stamp)
    traj = read_tum(trajectory)
    if not traj:
        sys.exit(trajectory + ': no poses')
    stamps = [p[0] for p in traj]
    pairs, unpaired, every_pair = [], 0, []
    for key, _, pose in scans(corrected):
        stamp = stamp_of.get(key)
        if stamp is None:
            unpaired += 1
            continue
        every_pair.append((stamp, pose))
        if stamp - stamps[0] > seconds:
            continue
        i = bisect.bisect_left(stamps, stamp - 1e-3)
        if i < len(traj) and abs(stamps[i] - stamp) <= 1e-3:
            pairs.append((pose, traj[i][1:]))
    if len(pairs) < 3:
        sys.exit('only %d scan pairs (%d corrected scans unpaired)' % (len(pairs), unpaired))
    n = len(pairs)
    th, tx, ty = fit_rigid(pairs)
    cos, sin = math.cos(th), math.sin(th)
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
    if tum_out:
        write_truth(tum_out, every_pair, tx, ty, th)


def write_truth(path, stamped_poses, tx, ty, th):
    """The corrected poses in the trajectory's frame: the inverse of corrected_from_trajectory."""
    cos, sin = math.cos(th), math.sin(th)
    with open(path, 'w') as out:
        for stamp, (x, y, heading) in sorted(stamped_poses):
            dx, dy = x - tx, y - ty
            yaw = heading - th
            x_m, y_m = cos * dx + sin * dy, -sin * dx + cos * dy
            out.write('%.6f %.6f %.6f 0 0 0 %.9f %.9f\n' %
                      (stamp, x_m, y_m, math.sin(yaw / 2), math.cos(yaw / 2)))
    print('wrote %d poses to %s' % (len(stamped_poses), path))


if __name__ == '__main__':
    main()
