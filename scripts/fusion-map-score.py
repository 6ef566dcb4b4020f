#!/usr/bin/env python3
"""The global map of a real log cut into robots, scored against the log's corrected-pose line map
(docs/fusion.md, "Figures: the global map on real logs").

scripts/fusion-map-score.py LOG.clf[.gz] [--parts N] [--offset S] [--build DIR] [--work DIR]
                            [--score-only] [--tolerance M] [-- extra pena-fusion options]

Runs scripts/fusion-split-log.py on LOG (N robots through `pena-fusion --lockstep` and N
`pena-entity --await-corrections 1`, B, C, ... with `--unknown-start`, loopback DDS profile;
--score-only: score the run already in --work), then prints:
- the segments and wall length of each entity's local map and of the published global map, and
  how the global map's walls are supported (pena-fusion's global_wall_support.csv, else the
  provenance: seen by one source or several, the walls' estimated error sd);
- for intel, aces and mit-csail: the global map's coverage and precision at --tolerance (0.2 m,
  10 deg) against the line map `pena map` builds from the radish-corrected log of the same run
  (data/radish-corrected/NAME-corrected.log.gz). That map is in the corrected log's frame; it is
  moved into the fusion's map frame by the rigid fit (least squares over positions, as
  scripts/radish-frame-fit.py) between the corrected poses and the team's published poses at the
  same scans (scans paired by identical ranges; an unknown start's poses from its placement on).
  Coverage: share of the reference's wall length within the tolerance of a global segment;
  precision: share of the global map's length within the tolerance of a reference wall
  (`pena eval --lines`).
Exit status 1 if a process failed.
"""
import argparse, bisect, importlib.util, json, math, re, subprocess, sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
CORRECTED = {'intel': 'intel', 'aces': 'aces', 'mit-csail': 'csail'}


def load(name):
    spec = importlib.util.spec_from_file_location(name.replace('-', '_'), REPO / 'scripts' / name)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


split = load('fusion-split-log.py')
frame_fit = load('radish-frame-fit.py')


def read_rows(path):
    """[(id, x1, y1, x2, y2, {column: text})] of a line CSV (header names the extra columns)."""
    rows = []
    with open(path) as f:
        header = f.readline().rstrip('\n').split(',')
        for line in f:
            c = line.rstrip('\n').split(',')
            if len(c) >= 5:
                rows.append((c[0], *map(float, c[1:5]), dict(zip(header[5:], c[5:]))))
    return rows


def length(row):
    return math.hypot(row[3] - row[1], row[4] - row[2])


def team_poses(work, pieces):
    """{stamp (log clock): (x, y)} of every published pose in the map frame."""
    trajectories = {p[0]: split.read_tum(work / p[0] / 'trajectory.tum', p[3]) for p in pieces}
    placed = split.placed_at(work, pieces, trajectories)
    poses = {}
    for entity_id, _, _, _, _ in pieces:
        since = -math.inf if entity_id == pieces[0][0] else placed.get(entity_id, math.inf)
        stamps, values = trajectories[entity_id]
        for t, p in zip(stamps, values):
            if t >= since:
                poses[t] = (p[0], p[1])
    return poses


def reference_in_map(log, name, work, build, pieces):
    """The corrected-pose line map moved into the fusion's map frame, its path and the fit."""
    corrected = REPO / 'data' / 'radish-corrected' / f"{CORRECTED[name]}-corrected.log.gz"
    reference = work / 'reference'
    if not (reference / 'lines.csv').exists():
        subprocess.run([str(build / 'tools/pena/pena'), 'map', '--quiet', '--log', str(corrected),
                        '--out', str(reference), '--min-length', '0.5'], check=True,
                       stdout=subprocess.DEVNULL)
    stamp_of = {}
    for key, stamp, _ in frame_fit.scans(str(log)):
        stamp_of.setdefault(key, stamp)
    poses = team_poses(work, pieces)
    stamps = sorted(poses)
    pairs = []
    for key, _, pose in frame_fit.scans(str(corrected)):
        stamp = stamp_of.get(key)
        if stamp is None:
            continue
        i = bisect.bisect_left(stamps, stamp - 1e-3)
        if i < len(stamps) and abs(stamps[i] - stamp) <= 1e-3:
            pairs.append((poses[stamps[i]], pose[:2]))  # (map frame, corrected frame)
    if len(pairs) < 3:
        sys.exit(f"fusion-map-score: only {len(pairs)} scans paired with {corrected}")
    th, tx, ty = frame_fit.fit_rigid(pairs)  # map_from_corrected
    c, s = math.cos(th), math.sin(th)
    moved = lambda x, y: (c * x - s * y + tx, s * x + c * y + ty)
    residuals = [math.hypot(*(m - v for m, v in zip(a, moved(*b)))) for a, b in pairs]
    out = work / 'reference-in-map.csv'
    with open(reference / 'lines.csv') as f, open(out, 'w') as w:
        w.write(f.readline())
        for line in f:
            col = line.rstrip('\n').split(',')
            x1, y1 = moved(float(col[1]), float(col[2]))
            x2, y2 = moved(float(col[3]), float(col[4]))
            w.write(','.join([col[0], f"{x1:.3f}", f"{y1:.3f}", f"{x2:.3f}", f"{y2:.3f}"] +
                             col[5:]) + '\n')
    rms = math.sqrt(sum(r * r for r in residuals) / len(residuals))
    return out, len(pairs), rms


def evaluate(build, walls, lines, tolerance):
    result = subprocess.run([str(build / 'tools/pena/pena'), 'eval', '--json', '--walls', str(walls),
                             '--lines', str(lines), '--distance-tolerance', str(tolerance)],
                            check=True, capture_output=True, text=True)
    return json.loads(result.stdout)['lines']


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('log')
    parser.add_argument('--parts', type=int, default=2)
    parser.add_argument('--offset', type=float)
    parser.add_argument('--build', default=str(REPO / 'build'))
    parser.add_argument('--work')
    parser.add_argument('--score-only', action='store_true')
    parser.add_argument('--tolerance', type=float, default=0.2, help='metres (default 0.2)')
    argv = sys.argv[1:]
    extra = argv[argv.index('--'):] if '--' in argv else []
    args = parser.parse_args(argv[:len(argv) - len(extra)])
    log = Path(args.log).resolve()
    name = re.sub(r'\.clf(\.gz)?$', '', log.name)
    build = Path(args.build).resolve()
    work = Path(args.work or f"/tmp/pena-fusion-map/{name}-{args.parts}").resolve()
    command = [sys.executable, str(REPO / 'scripts' / 'fusion-split-log.py'), str(log), '--parts',
               str(args.parts), '--build', str(build), '--work', str(work)]
    if args.offset is not None:
        command += ['--offset', str(args.offset)]
    if args.score_only:
        command.append('--score-only')
    if subprocess.run(command + extra).returncode != 0:
        return 1
    pieces = split.cut(log, args.parts, args.offset, work)

    print()
    print(f"| map | segments | wall m |")
    print("|---|---|---|")
    for entity_id, _, _, _, _ in pieces:
        local = read_rows(work / entity_id / 'line_map.csv')
        print(f"| {entity_id}'s local map | {len(local)} | {sum(map(length, local)):.0f} |")
    global_map = read_rows(work / 'fusion' / 'global_map.csv')
    print(f"| published global map | {len(global_map)} | {sum(map(length, global_map)):.0f} |")
    support = {}
    support_path = work / 'fusion' / 'global_wall_support.csv'
    if support_path.exists():
        with open(support_path) as f:
            f.readline()
            for line in f:
                wall_id, seen_by, sd = line.rstrip('\n').split(',')
                support[wall_id] = (seen_by.split(), float(sd))
    by_sources = {}
    for row in global_map:
        entities = {k.rsplit(':', 1)[0] for k in row[5].get('provenance', '').split()}
        seen, sd = support.get(row[0], (sorted(entities), math.nan))
        entry = by_sources.setdefault(len(seen), [0, 0.0, 0.0])
        entry[0] += 1
        entry[1] += length(row)
        entry[2] += length(row) * sd
    for n in sorted(by_sources):
        count, metres, sd = by_sources[n]
        print(f"  seen by {n} source{'' if n == 1 else 's'}: {count} segments, {metres:.0f} m"
              + ("" if math.isnan(sd) else f", length-weighted error sd {sd / metres:.3f} m"))
    if name not in CORRECTED:
        print(f"\n{name}: no radish-corrected log, no coverage / precision")
        return 0
    reference, paired, rms = reference_in_map(log, name, work, build, pieces)
    score = evaluate(build, reference, work / 'fusion' / 'global_map.csv', args.tolerance)
    print(f"\nagainst the corrected-pose line map ({score['walls']} walls, "
          f"{score['wall_length_m']:.0f} m; frame fitted on {paired} scans, residual RMS {rms:.3f} m):"
          f" coverage {100 * score['coverage']:.1f} %, precision {100 * score['precision']:.1f} % "
          f"at {args.tolerance:g} m")
    return 0


if __name__ == '__main__':
    sys.exit(main())
