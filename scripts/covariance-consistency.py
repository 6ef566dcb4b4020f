#!/usr/bin/env python3
"""Whether the odometry's covariance is honest against ground truth (docs/odometry.md).

scripts/covariance-consistency.py RUN_DIR/odometry.csv TRUTH.tum [--label NAME]

For every scan with a true pose at its stamp (within 1 ms) and a positive-definite position
covariance, the position error e and its normalised squared error e^T P^-1 e (NEES, chi-square
with 2 degrees of freedom when P is right: mean 2, 95 % of scans below 5.99, 99 % below 9.21);
and the heading error against sd_theta (95 % within 1.96 sd). Prints one line:

  NAME: N scans (.. singular ...), inside 95 % ellipse 0.xx, 99 % 0.xx, mean NEES x.xx, heading within 1.96 sd
  0.xx, median sd 0.xxx m against median error 0.xxx m, end sd 0.xxx m against end error 0.xxx m

Far below 0.95 inside means overconfident; a mean NEES far below 2 means overcautious.
A singular covariance with no error (the start) is counted apart; one with an error (certain,
and wrong) counts as outside every ellipse and is left out of the mean NEES.

"""
import csv, math, sys

from tum_poses import read_tum

CHI2_2_95 = 5.991
CHI2_2_99 = 9.210
SINGULAR_ERROR_M = 1e-3  # a singular covariance is right only where the error is nil (the start)

def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))

def report(name, nees, heading_inside, sds, errors, singular, last, misses):
    n = len(nees) + misses
    inside_95 = sum(v <= CHI2_2_95 for v in nees) / n
    inside_99 = sum(v <= CHI2_2_99 for v in nees) / n
    print(f'{name}: {n} scans ({singular} singular without error, {misses} singular with one), '
          f'inside 95 % ellipse {inside_95:.2f}, 99 % {inside_99:.2f}, mean NEES {sum(nees) / len(nees):.2f}, '
          f'heading within 1.96 sd {heading_inside / len(nees):.2f}, '
          f'median sd {median(sds):.3f} m against median error {median(errors):.3f} m, '
          f'end sd {last[0]:.3f} m against end error {last[1]:.3f} m')

def median(values):
    values = sorted(values)
    return values[len(values) // 2] if values else float('nan')

def main():
    args = sys.argv[1:]
    label = None
    if '--label' in args:
        i = args.index('--label')
        label = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    truth = read_tum(args[1])
    nees, heading_inside, sds, errors, singular, zero_variance_misses = [], 0, [], [], 0, 0
    last = None
    with open(args[0]) as f:
        for row in csv.DictReader(f):
            t = truth.get(round(float(row['stamp']), 3))
            if t is None:
                continue
            ex, ey = float(row['x']) - t[0], float(row['y']) - t[1]
            eth = wrap(float(row['theta']) - t[2])
            sxx, syy = float(row['sd_x']) ** 2, float(row['sd_y']) ** 2
            sxy = float(row['cov_xy'])
            det = sxx * syy - sxy * sxy
            sd_theta = float(row['sd_theta'])
            if det <= 0.0 or sd_theta <= 0.0:
                if math.hypot(ex, ey) > SINGULAR_ERROR_M:
                    zero_variance_misses += 1  # certain, and wrong: outside every ellipse
                else:
                    singular += 1
                continue
            nees.append((syy * ex * ex - 2 * sxy * ex * ey + sxx * ey * ey) / det)
            heading_inside += abs(eth) <= 1.96 * sd_theta
            sds.append(math.sqrt(0.5 * (sxx + syy)))
            errors.append(math.hypot(ex, ey))
            last = (sds[-1], errors[-1])
    if not nees:
        sys.exit('no scan with a true pose and a covariance')
    report(label or args[0], nees, heading_inside, sds, errors, singular, last, zero_variance_misses)

if __name__ == '__main__':
    main()
