#!/usr/bin/env python3
"""How well a trajectory follows the walker from scan to scan (docs/dead-reckoning.md).

scripts/step-errors.py TRAJECTORY.tum TRUTH.tum [--spans 0.25,1]

For every pose and every span S, the displacement over the S seconds before it (in the frame of
the earlier pose, so a drifted heading does not count) against the same displacement of the
truth; prints the RMS, the 99th percentile and the largest error per span, and the share of
0.25 s steps that go backwards along the truth's own step while the walker moves on (> 5 cm).
Poses are matched to the truth by stamp within 1 ms.
"""
import math, sys

from tum_poses import between, read_tum


def relative(a, b):
    return between(a, b)[:2]

def main():
    args = sys.argv[1:]
    spans = [0.25, 1.0]
    if '--spans' in args:
        i = args.index('--spans')
        spans = [float(v) for v in args[i + 1].split(',')]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    est, truth = read_tum(args[0]), read_tum(args[1])
    stamps = sorted(t for t in est if t in truth)
    have = set(stamps)
    for span in spans:
        errors, backwards, moving = [], 0, 0
        for t in stamps:
            t0 = round(t - span, 3)
            if t0 not in have:
                continue
            de = relative(est[t0], est[t])
            dt = relative(truth[t0], truth[t])
            errors.append(math.hypot(de[0] - dt[0], de[1] - dt[1]))
            length = math.hypot(*dt)
            if span == 0.25 and length > 0.05:
                moving += 1
                if (de[0] * dt[0] + de[1] * dt[1]) / length < 0.0:
                    backwards += 1
        if not errors:
            print(f'span {span} s: no pairs')
            continue
        errors.sort()
        rms = math.sqrt(sum(e * e for e in errors) / len(errors))
        p99 = errors[min(len(errors) - 1, int(0.99 * len(errors)))]
        line = f'span {span:.2f} s: RMS {rms:.3f} m, p99 {p99:.3f} m, max {errors[-1]:.3f} m ({len(errors)} pairs)'
        if span == 0.25:
            line += f'; backwards {backwards} of {moving} moving steps'
        print(line)

if __name__ == '__main__':
    main()
