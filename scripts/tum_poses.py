"""TUM trajectories for the evaluation scripts (docs/formats.md): stamp x y z qx qy qz qw.

read_tum(path) gives {stamp rounded to the millisecond: (x, y, heading)}, so that poses of two
files are matched by stamp within 1 ms, as `pena eval` does. between(a, b) is b in a's frame.
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


def between(a, b):
    """Pose b = (x, y, heading) in the frame of pose a: (x, y, heading in [-pi, pi])."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], 2 * math.pi))
