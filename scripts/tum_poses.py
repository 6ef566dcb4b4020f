"""TUM trajectories for the evaluation scripts (docs/formats.md): stamp x y z qx qy qz qw.

read_tum(path) gives {stamp rounded to the millisecond: (x, y, heading)}, so that poses of two
files are matched by stamp within 1 ms, as `pena eval` does.
"""
import math


def read_tum(path):
    poses = {}
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        f = line.split()
        poses[round(float(f[0]), 3)] = (float(f[1]), float(f[2]), 2 * math.atan2(float(f[6]), float(f[7])))
    return poses
