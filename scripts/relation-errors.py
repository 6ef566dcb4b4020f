#!/usr/bin/env python3
"""Where a run's relation error comes from (docs/odometry.md).

scripts/relation-errors.py RUN_DIR LOG.clf.gz LOG.relations [--steps N]

RUN_DIR is a `pena odometry` output directory (trajectory.tum, odometry.csv) of the CARMEN log.
Prints: mean error, contribution by relation span, the top relations, and the heading error
function h(t) reconstructed from the relations' signed rotation errors (least squares over the
relation graph; 400 Gauss-Seidel sweeps, so the steps are approximate), its largest steps, and for each step our per-scan heading increments against the
CARMEN odometry's around it.
"""
import bisect, gzip, math, sys

def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi

def read_tum(path):
    st, poses = [], []
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        f = line.split()
        t, x, y, qz, qw = float(f[0]), float(f[1]), float(f[2]), float(f[6]), float(f[7])
        st.append(t); poses.append((x, y, 2 * math.atan2(qz, qw)))
    return st, poses

def read_csv(path):
    rows = []
    with open(path) as f:
        head = f.readline().strip().split(',')
        for line in f:
            rows.append(dict(zip(head, line.strip().split(','))))
    return rows

def read_odom(path):
    out = {}
    with gzip.open(path, 'rt') as f:
        for line in f:
            if line.startswith('FLASER'):
                p = line.split()
                out[round(float(p[-3]), 6)] = (float(p[-6]), float(p[-5]), float(p[-4]))
    return out

def find(st, t, tol=0.001):
    i = bisect.bisect_left(st, t)
    best = None
    for j in (i - 1, i):
        if 0 <= j < len(st) and abs(st[j] - t) <= tol and (best is None or abs(st[j] - t) < abs(st[best] - t)):
            best = j
    return best

def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, wrap(b[2] - a[2]))

def main():
    run, log, rel = sys.argv[1:4]
    nsteps = int(sys.argv[sys.argv.index('--steps') + 1]) if '--steps' in sys.argv else 8
    st, poses = read_tum(run + '/trajectory.tum')
    rows = read_csv(run + '/odometry.csv')
    errs = []
    for line in open(rel):
        f = line.split()
        if len(f) < 8 or f[0].startswith("#"):
            continue
        t1, t2 = float(f[0]), float(f[1])
        m = (float(f[2]), float(f[3]), float(f[7]))
        i, j = find(st, t1), find(st, t2)
        if i is None or j is None:
            continue
        e = between(poses[i], poses[j])
        # |translation of m^-1 * e| = |e.xy - m.xy| (a rotation keeps lengths), as pena eval
        ex, ey = e[0] - m[0], e[1] - m[1]
        terr = math.hypot(ex, ey)
        rerr = wrap(e[2] - m[2])
        errs.append((t1, t2, terr, rerr, i, j, math.hypot(m[0], m[1])))
    n = len(errs)
    mean = sum(e[2] for e in errs) / n
    print(f'relations used {n}, mean translational error {mean:.4f} m, mean |rot| {sum(abs(e[3]) for e in errs)/n*180/math.pi:.3f} deg')
    total = sum(e[2] for e in errs)
    bins = [(0, 2), (2, 10), (10, 60), (60, 300), (300, math.inf)]
    print('span_s        count  mean_err_m  share_of_sum')
    for lo, hi in bins:
        sel = [e for e in errs if lo <= e[1] - e[0] < hi]
        if sel:
            s = sum(e[2] for e in sel)
            print(f'{lo:>5}-{hi:<7.0f} {len(sel):6d}  {s/len(sel):9.4f}  {s/total:6.1%}')
    srt = sorted(errs, key=lambda e: -e[2])
    k50 = 0; acc = 0
    while acc < total / 2:
        acc += srt[k50][2]; k50 += 1
    print(f'half of the error sum comes from {k50} relations; top 5:')
    for e in srt[:5]:
        print(f'  t {e[0]-st[0]:8.1f}-{e[1]-st[0]:8.1f} s (scans {e[4]}-{e[5]}) err {e[2]:.3f} m rot {e[3]*180/math.pi:+.2f} deg')
    # Heading error function h at relation stamps: e_ij = h_j - h_i, least squares (Gauss-Seidel
    # on the graph Laplacian, h at the first stamp fixed to 0).
    nodes = sorted({e[4] for e in errs} | {e[5] for e in errs})
    idx = {v: k for k, v in enumerate(nodes)}
    adj = [[] for _ in nodes]
    for e in errs:
        a, b = idx[e[4]], idx[e[5]]
        adj[a].append((b, -e[3])); adj[b].append((a, e[3]))  # h_a = h_b - r ; h_b = h_a + r
    h = [0.0] * len(nodes)
    for _ in range(400):
        for k in range(1, len(nodes)):
            if adj[k]:
                h[k] = sum(h[o] + r for o, r in adj[k]) / len(adj[k])
    steps = [(h[k] - h[k - 1], nodes[k - 1], nodes[k]) for k in range(1, len(nodes))]
    big = sorted(steps, key=lambda s: -abs(s[0]))[:nsteps]
    print(f'heading error h(t): final {h[-1]*180/math.pi:+.2f} deg, max |h| {max(abs(x) for x in h)*180/math.pi:.2f} deg; largest steps between relation stamps:')
    odom = read_odom(log)
    for dh, a, b in sorted(big, key=lambda s: s[1]):
        print(f'  scans {a}-{b} (t {st[a]-st[0]:.1f}-{st[b]-st[0]:.1f} s): step {dh*180/math.pi:+.2f} deg')
        lo, hi = max(a - 2, 0), min(b + 2, len(rows) - 1)
        if hi - lo > 40:
            continue
        for r in range(lo + 1, hi + 1):
            ours = wrap(poses[r][2] - poses[r - 1][2])
            o1, o0 = odom.get(round(st[r], 6)), odom.get(round(st[r - 1], 6))
            od = wrap(o1[2] - o0[2]) if o1 and o0 else float('nan')
            row = rows[r]
            print(f'     scan {r:5d} dt {st[r]-st[r-1]:.3f} ours {ours*180/math.pi:+7.2f} odom {od*180/math.pi:+7.2f} '
                  f'diff {(ours-od)*180/math.pi:+6.2f} {row["status"]:10s} score {float(row["score"]):.2f} '
                  f'kf {row["reference_changed"]} wide {row["wide_search"]} gated {row["gated"]} stale {row["stale"]}')

if __name__ == '__main__':
    main()
