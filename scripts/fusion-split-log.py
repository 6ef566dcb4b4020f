#!/usr/bin/env python3
"""One real log as a team: the fusion on real data (docs/fusion.md, "Figures: real logs").

scripts/fusion-split-log.py LOG.clf[.gz] [--relations FILE] [--parts N] [--offset S]
                            [--single] [--build DIR] [--work DIR] [-- extra pena-fusion options]

Cuts a CARMEN log at its scans into N consecutive pieces (default 2: at its middle scan), each a
CARMEN log of its own, and runs them as N robots (entity ids A, B, C, ...) through one
`pena-fusion --lockstep` and N `pena-entity --await-corrections` on the loopback DDS profile, on
a DDS domain of their own. A keeps the log's start pose; the others start with
`--unknown-start` and must be placed by the fusion. The pieces keep the log's stamps (B starts
where A ended, as a second robot sent in after the first), or with --offset S piece k starts
k x S seconds after A (stamps moved back, and forward again before scoring).

Prints, from the relation file (default: LOG's name with .relations):
- the relations whose two stamps fall in one piece (within an entity) and in two pieces
  (cross-entity: the team's consistency), mean / max translational error, mean rotational error
  (Kuemmerle et al. 2009, as `pena eval --relations`) of the poses each entity published
  (trajectory.tum: in the map frame once placed);
- with --single, the same relations scored on the single-run SLAM of the whole log
  (`pena map --ignore-logged-poses`): what one robot that saw every scan achieves;
- when each unknown start was placed (mission seconds after the piece's first scan);
- the global map's segments against each local map's, and how much of each local map's wall
  length the global map carries (a local segment whose key "<entity>:<id>" is in some global
  segment's provenance).
Exit status 1 if a process failed.
"""
import argparse, bisect, fcntl, gzip, math, os, re, signal, subprocess, sys, time
from decimal import Decimal
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
IDS = "ABCDEFGH"


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def open_text(path):
    return gzip.open(path, 'rt') if str(path).endswith('.gz') else open(path)


# --- cutting the log -----------------------------------------------------------------------

STAMPED = {'FLASER': -3, 'ODOM': -3, 'ROBOTLASER1': -3, 'RAWLASER1': -3}  # ipc_timestamp field


def read_log(path):
    """The header lines (comments, PARAM) and the stamped messages (stamp, line) in file order."""
    header, messages = [], []
    for number, line in enumerate(open_text(path), 1):
        fields = line.split()
        if not fields or fields[0].startswith('#') or fields[0] == 'PARAM':
            header.append(line)
            continue
        if fields[0] not in STAMPED:
            continue
        try:
            stamp = float(fields[STAMPED[fields[0]]])
        except (ValueError, IndexError):
            sys.exit(f"fusion-split-log: {path}:{number}: no ipc_timestamp in a {fields[0]} line")
        messages.append((stamp, fields[0], line))
    if not any(kind != 'ODOM' for _, kind, _ in messages):
        sys.exit(f"fusion-split-log: {path}: no laser scans")
    return header, messages


def shift_stamp(text, shift):
    """`text` minus `shift` seconds, printed with the same decimals (exact: Decimal)."""
    decimals = len(text.split('.')[1]) if '.' in text else 0
    return f"{Decimal(text) - shift:.{decimals}f}"


def shifted(line, shift):
    """A message line with its ipc and logger timestamps moved back by `shift` seconds."""
    fields = line.split()
    fields[-3] = shift_stamp(fields[-3], shift)
    fields[-1] = shift_stamp(fields[-1], shift)
    return ' '.join(fields) + '\n'


def cut(log, parts, offset_s, work):
    """Writes work/piece-<id>.clf per part; returns [(id, first_stamp, last_stamp, shift)]."""
    header, messages = read_log(log)
    scans = [i for i, (_, kind, _) in enumerate(messages) if kind != 'ODOM']
    bounds = [0] + [scans[len(scans) * k // parts] for k in range(1, parts)] + [len(messages)]
    pieces = []
    first0 = messages[0][0]
    for k in range(parts):
        chunk = messages[bounds[k]:bounds[k + 1]]
        first = chunk[0][0]
        # Decimal shift so the rewritten stamps are exact; piece k starts k * offset after A.
        shift = Decimal(0) if offset_s is None else (
            Decimal(repr(first)) - Decimal(repr(first0)) - Decimal(repr(k * offset_s)))
        path = work / f"piece-{IDS[k]}.clf"
        with open(path, 'w') as out:
            out.writelines(header)
            for _, _, line in chunk:
                out.write(shifted(line, shift) if shift else line)
        pieces.append((IDS[k], first, chunk[-1][0], float(shift), path))
    return pieces


# --- running the team ----------------------------------------------------------------------

def lock_domain():
    """The first DDS domain in 30..99 no other run holds (deploy/dds/domain-lock.sh's locks)."""
    for domain in range(30, 100):
        handle = open(f"/tmp/pena-dds-domain-{domain}.lock", 'w')
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return domain, handle
        except OSError:
            handle.close()
    sys.exit("fusion-split-log: no free DDS domain in 30..99")


def run_team(build, pieces, work, interval_s, fusion_extra):
    domain, lock = lock_domain()
    dds = REPO / 'deploy' / 'dds'
    dds_args = ['--domain', str(domain), '--profiles-file', str(dds / 'pena-loopback.xml'),
                '--profiles-file', str(dds / 'pena-qos.xml')]
    env = dict(os.environ, FASTRTPS_DEFAULT_PROFILES_FILE=str(dds / 'pena-loopback.xml'))
    logs = work / 'logs'
    logs.mkdir(exist_ok=True)
    started = []

    def spawn(args, name):
        out = open(logs / f"{name}.log", 'w')
        process = subprocess.Popen(args, stdout=out, stderr=subprocess.STDOUT, env=env)
        started.append(process)
        return process

    ids = ','.join(p[0] for p in pieces)
    fusion = spawn([str(build / 'services/fusion/pena-fusion'), '--state-dir', str(work / 'state'),
                    '--out', str(work / 'fusion'), '--lockstep', '--lockstep-entities', ids,
                    '--correction-interval', str(interval_s)] + dds_args + fusion_extra, 'fusion')
    entities = []
    for entity_id, _, _, _, path in pieces:
        args = [str(build / 'services/entity/pena-entity'), '--input', str(path), '--entity-id',
                entity_id, '--rate', '0', '--out', str(work / entity_id), '--wait-for-readers', '30',
                '--linger', '5', '--await-corrections', str(interval_s)] + dds_args
        if entity_id != 'A':
            args.append('--unknown-start')
        entities.append((entity_id, spawn(args, entity_id)))
    failed = False
    try:
        for entity_id, process in entities:
            if process.wait() != 0:
                print(f"fusion-split-log: pena-entity {entity_id} failed, see {logs}/{entity_id}.log",
                      file=sys.stderr)
                failed = True
        time.sleep(1.0)
        fusion.send_signal(signal.SIGTERM)
        if fusion.wait(timeout=60) != 0:
            print(f"fusion-split-log: pena-fusion failed, see {logs}/fusion.log", file=sys.stderr)
            failed = True
    finally:
        for process in started:
            if process.poll() is None:
                process.kill()
                process.wait()
        lock.close()
    return not failed


# --- scoring -------------------------------------------------------------------------------

def read_tum(path, shift=0.0):
    stamps, poses = [], []
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        f = line.split()
        stamps.append(float(f[0]) + shift)
        poses.append((float(f[1]), float(f[2]), 2 * math.atan2(float(f[6]), float(f[7]))))
    order = sorted(range(len(stamps)), key=stamps.__getitem__)
    return [stamps[i] for i in order], [poses[i] for i in order]


def find(stamps, t, tolerance_s=0.001):
    i = bisect.bisect_left(stamps, t)
    best = None
    for j in (i - 1, i):
        if 0 <= j < len(stamps) and abs(stamps[j] - t) <= tolerance_s:
            if best is None or abs(stamps[j] - t) < abs(stamps[best] - t):
                best = j
    return best


def relation_error(p1, p2, relation):
    """Kuemmerle et al. 2009 eq. (1): relation^-1 (p1^-1 p2), translation and rotation apart."""
    dx, dy = p2[0] - p1[0], p2[1] - p1[1]
    c, s = math.cos(p1[2]), math.sin(p1[2])
    ex, ey = c * dx + s * dy - relation[0], -s * dx + c * dy - relation[1]
    return math.hypot(ex, ey), abs(wrap(p2[2] - p1[2] - relation[2]))


def read_relations(path):
    relations = []
    for number, line in enumerate(open(path), 1):
        f = line.split()
        if not f:
            continue
        if len(f) < 8:
            sys.exit(f"fusion-split-log: {path}:{number}: a relation needs 8 fields")
        relations.append((float(f[0]), float(f[1]), (float(f[2]), float(f[3]), float(f[7]))))
    return relations


def piece_of(pieces, t):
    for entity_id, first, last, _, _ in pieces:
        if first - 1e-6 <= t <= last + 1e-6:
            return entity_id
    return None


def score(relations, pieces, lookup, placed_from=None):
    """{'within': [...], 'cross': [...]} of (translation m, rotation rad), and how many relations
    were not scored: a stamp without a pose, or before its entity was placed (placed_from: the
    first placed stamp of each unknown start, log stamps). lookup(id, t) -> pose or None."""
    classes = {'within': [], 'cross': []}
    skipped = unplaced = 0
    for t1, t2, relation in relations:
        e1, e2 = piece_of(pieces, t1), piece_of(pieces, t2)
        if e1 is None or e2 is None:
            skipped += 1
            continue
        if placed_from is not None and any(
                t < placed_from.get(e, -math.inf) for e, t in ((e1, t1), (e2, t2))):
            unplaced += 1
            continue
        p1, p2 = lookup(e1, t1), lookup(e2, t2)
        if p1 is None or p2 is None:
            skipped += 1
            continue
        classes['within' if e1 == e2 else 'cross'].append(relation_error(p1, p2, relation))
    return classes, skipped, unplaced


def row(name, errors):
    if not errors:
        return f"| {name} | 0 | - | - | - |"
    t = [e[0] for e in errors]
    r = [math.degrees(e[1]) for e in errors]
    return (f"| {name} | {len(errors)} | {sum(t) / len(t):.3f} | {max(t):.3f} | "
            f"{sum(r) / len(r):.2f} |")


def read_lines(path):
    """[(id, length_m, extra columns)] of a line CSV."""
    rows = []
    with open(path) as f:
        f.readline()
        for line in f:
            c = line.rstrip('\n').split(',')
            if len(c) >= 5:
                length = math.hypot(float(c[3]) - float(c[1]), float(c[4]) - float(c[2]))
                rows.append((c[0], length, c[5:]))
    return rows


def placed_at(work, pieces, trajectories):
    """{entity: first placed stamp (log stamps)} of the unknown starts pena-fusion placed
    ("placed at" in its log); the entity's poses jump from its own frame to the map's there."""
    placed = {}
    text = (work / 'logs' / 'fusion.log').read_text(errors='replace')
    for entity_id, _, _, _, _ in pieces[1:]:
        if not re.search(rf"\b{entity_id}: placed at", text):
            continue
        stamps, poses = trajectories[entity_id]
        placed[entity_id] = math.inf
        for i in range(1, len(poses)):
            if math.hypot(poses[i][0] - poses[i - 1][0], poses[i][1] - poses[i - 1][1]) > 1.0:
                placed[entity_id] = stamps[i]
                break
    return placed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('log')
    parser.add_argument('--relations')
    parser.add_argument('--parts', type=int, default=2)
    parser.add_argument('--offset', type=float)
    parser.add_argument('--interval', type=float, default=1.0,
                        help='mission seconds between correction attempts per entity')
    parser.add_argument('--single', action='store_true')
    parser.add_argument('--build', default=str(REPO / 'build'))
    parser.add_argument('--work')
    parser.add_argument('--score-only', action='store_true',
                        help='score the run already in --work')
    argv = sys.argv[1:]
    fusion_extra = argv[argv.index('--') + 1:] if '--' in argv else []  # extra pena-fusion options
    args = parser.parse_args(argv[:argv.index('--')] if '--' in argv else argv)
    log = Path(args.log)
    if not 2 <= args.parts <= len(IDS):
        sys.exit(f"fusion-split-log: --parts must be in 2..{len(IDS)}, got {args.parts}")
    name = re.sub(r'\.clf(\.gz)?$', '', log.name)
    relations_path = Path(args.relations) if args.relations else log.with_name(name + '.relations')
    if not relations_path.exists():
        sys.exit(f"fusion-split-log: no relation file {relations_path} (--relations)")
    build = Path(args.build).resolve()
    work = Path(args.work or f"/tmp/pena-fusion-split/{name}-{args.parts}").resolve()
    work.mkdir(parents=True, exist_ok=True)

    pieces = cut(log, args.parts, args.offset, work)
    if not args.score_only:
        for binary in ('services/fusion/pena-fusion', 'services/entity/pena-entity'):
            if not (build / binary).exists():
                sys.exit(f"fusion-split-log: {build / binary} not built")
        for sub in ['state', 'fusion'] + [p[0] for p in pieces]:
            subprocess.run(['rm', '-rf', str(work / sub)], check=True)
        if not run_team(build, pieces, work, args.interval, fusion_extra):
            return 1

    trajectories = {p[0]: read_tum(work / p[0] / 'trajectory.tum', p[3]) for p in pieces}

    def team_pose(entity_id, t):
        stamps, poses = trajectories[entity_id]
        i = find(stamps, t)
        return None if i is None else poses[i]

    relations = read_relations(relations_path)
    placed = placed_at(work, pieces, trajectories)
    unplaced_from = {p[0]: math.inf for p in pieces[1:]}
    unplaced_from.update(placed)
    team, skipped, unplaced = score(relations, pieces, team_pose, unplaced_from)
    print(f"{log.name}: {args.parts} entities ({', '.join(p[0] for p in pieces)}), "
          f"{'log stamps' if args.offset is None else f'offset {args.offset:g} s'}, "
          f"correction interval {args.interval:g} s; {len(relations)} relations, {unplaced} "
          f"before an entity was placed, {skipped} with a stamp without a pose")
    print()
    print("| relations | n | mean m | max m | mean deg |")
    print("|---|---|---|---|---|")
    print(row("team, within an entity", team['within']))
    print(row("team, cross-entity", team['cross']))
    if args.single:
        single_dir = work / 'single'
        if not (single_dir / 'trajectory.tum').exists():
            subprocess.run([str(build / 'tools/pena/pena'), 'map', '--quiet',
                            '--ignore-logged-poses', '--log', str(log), '--out', str(single_dir)],
                           check=True, stdout=subprocess.DEVNULL)
        single = read_tum(single_dir / 'trajectory.tum')
        lone, _, _ = score(relations, pieces,
                           lambda _, t: (lambda i: None if i is None else single[1][i])(
                               find(single[0], t)), unplaced_from)
        print(row("single-run SLAM, within", lone['within']))
        print(row("single-run SLAM, cross", lone['cross']))
    print()
    for entity_id, first, _, shift, _ in pieces[1:]:
        when = placed.get(entity_id, math.inf)
        print(f"{entity_id} (unknown start): " + ("not placed" if when == math.inf else
              f"placed {when - first:.1f} s after its first scan"))
    global_map = read_lines(work / 'fusion' / 'global_map.csv')
    carried = set()
    for _, _, extra in global_map:
        if len(extra) >= 4:
            carried.update(extra[3].split())
    print()
    print(f"global map: {len(global_map)} segments, "
          f"{sum(r[1] for r in global_map):.0f} m of wall")
    print("| local map | segments | wall m | carried by the global map |")
    print("|---|---|---|---|")
    for entity_id, _, _, _, _ in pieces:
        local = read_lines(work / entity_id / 'line_map.csv')
        total = sum(r[1] for r in local)
        kept = sum(r[1] for r in local if f"{entity_id}:{r[0]}" in carried)
        print(f"| {entity_id} | {len(local)} | {total:.0f} | "
              f"{100 * kept / total if total else 0:.1f} % |")
    return 0


if __name__ == '__main__':
    sys.exit(main())
