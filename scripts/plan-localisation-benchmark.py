#!/usr/bin/env python3
"""The plan localisation benchmark: `pena localise` with its defaults on every real building we
have, on a line map built from the building's corrected poses; one table per building
(docs/localisation.md, "Plan localisation benchmark").

For each radish-corrected log (intel, aces, csail, seattle, orebro):
  1. `pena map --log CORRECTED --out MAP` builds the line map from the corrected poses;
  2. per seed, `pena export --perturb-odometry SEED` perturbs the log's odometry with the noise
     model of the generalisation benchmark (scale errors, heading random walk, sudden slips of
     5-30 deg; sim::OdometryNoiseModel) and writes the corrected poses as truth;
  3. `pena localise` localises the perturbed log on MAP from the known start (the first corrected
     pose) and with `--global`;
  4. the trajectory is scored against the corrected poses, scan by scan.

Columns (per mode, over seeds): error against the corrected poses (mean, 95th percentile, max, m;
the global mode scores the scans after its start was decided), lost: seconds outside the plan per
run (status.csv `lost`, or `outside_map` where the column is missing), re-acq: the longest lost
interval until the plan matched again (s and metres walked; "never" if one did not end), outside:
seconds per run the plan rounds judged the entity outside the plan (status `outside_map`), wrong:
seconds per run with an error over 0.5 m, anchor: seconds until a global start was decided, scans/s.

Logs nobody here has seen are run the same way: --corrected LOG (a log with corrected poses,
perturbed like the radish ones), or --log RAW --truth CORRECTED (a raw log of the same run
localised as it is on the map from CORRECTED and scored against its poses where the scan stamps
agree; the known start is the corrected pose at the raw log's first scan). --raw adds the raw
Freiburg logs (intel, aces, mit-csail) on their radish maps, localised as they are (start mode at
0,0,0, where the radish-corrected frame puts the Freiburg log's start) and scored twice: on their
relations (rows "freiburg MODE relations": relation error mean, 95th percentile, max) and against
the corrected poses (rows "freiburg MODE"). The two logs' clocks differ, so the corrected scans
are paired with the Freiburg scans by identical ranges (scripts/radish-frame-fit.py); the map
frame is the corrected frame, so the error needs no fit (the rigid fit of the trajectory onto
the corrected poses is printed as a check that the frames agree).

The last lines check the issue's acceptance on every perturbed row: mean under 0.10 m, 95th
percentile under 0.30 m, and every lost interval found within 20 m of travel (one the log ended
in counts if it lasted longer). The total wall time is printed.

  scripts/plan-localisation-benchmark.py [--build DIR] [--work DIR] [--buildings intel,aces,...]
      [--seeds N] [--modes start,global] [--jobs N] [--raw] [--corrected LOG]...
      [--log RAW --truth CORRECTED]... [--json FILE] [--resume] [-- extra pena localise options]
"""
import argparse
import bisect
import concurrent.futures
import csv
import json
import math
import os
import shutil
import importlib.util
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RADISH = ["intel", "aces", "csail", "seattle", "orebro"]
RAW = {"intel": "intel", "aces": "aces", "mit-csail": "csail"}  # Freiburg log -> radish map
WRONG_M = 0.5  # an error above this counts as "wrong" time
# The acceptance on the perturbed runs.
ACCEPT_MEAN_M, ACCEPT_P95_M, ACCEPT_LOST_M = 0.10, 0.30, 20.0


def radish_frame_fit():
    """scripts/radish-frame-fit.py as a module (scan pairing and the rigid fit)."""
    spec = importlib.util.spec_from_file_location("radish_frame_fit", ROOT / "scripts" / "radish-frame-fit.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def datasets_dir():
    env = os.environ.get("PENA_DATASETS") or os.environ.get("PENA_DATA_DIR")
    if env:
        return Path(env)
    for candidate in (ROOT / "data", ROOT.parent / "shared" / "datasets"):
        if (candidate / "radish-corrected").is_dir():
            return candidate
    sys.exit("plan-localisation-benchmark: no datasets found (set PENA_DATASETS)")


RESUME = False  # --resume: a step whose output exists is not run again


def run(cmd, log_path, output=None):
    if RESUME and output is not None and Path(output).exists():
        return
    with open(log_path, "w") as log:
        result = subprocess.run([str(c) for c in cmd], stdout=log, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed (exit {result.returncode}); see {log_path}")


def read_tum(path):
    """[(stamp, x, y, theta)] from a TUM file (planar: yaw from the quaternion)."""
    poses = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            v = line.split()
            if len(v) != 8:
                raise ValueError(f"{path}:{number}: expected 8 TUM fields, got {len(v)}")
            t, x, y, qz, qw = float(v[0]), float(v[1]), float(v[2]), float(v[6]), float(v[7])
            poses.append((t, x, y, 2.0 * math.atan2(qz, qw)))
    return poses


def match(estimate, truth, tolerance_s=0.01):
    """Pairs (estimate pose, truth pose) whose stamps agree within tolerance_s."""
    stamps = [p[0] for p in truth]
    pairs = []
    for e in estimate:
        i = bisect.bisect_left(stamps, e[0])
        best = min((j for j in (i - 1, i) if 0 <= j < len(truth)), key=lambda j: abs(stamps[j] - e[0]), default=None)
        if best is not None and abs(stamps[best] - e[0]) <= tolerance_s:
            pairs.append((e, truth[best]))
    return pairs


def percentile(values, q):
    if not values:
        return None
    s = sorted(values)
    return s[min(len(s) - 1, int(math.ceil(q * len(s))) - 1)]


def lost_intervals(status_csv, truth, column):
    """[(start s, end s or None, metres walked on truth)] of the stretches the run was lost
    (column "lost") or outside the plan (column "outside")."""
    with open(status_csv) as f:
        rows = list(csv.DictReader(f))
    intervals, start = [], None
    for r in rows:
        if column == "lost":
            lost = r["lost"] == "1" if "lost" in r else r["status"] == "outside_map"
        else:
            lost = r["status"] == "outside_map"
        t = float(r["stamp"])
        if lost and start is None:
            start = t
        elif not lost and start is not None:
            intervals.append((start, t))
            start = None
    if start is not None:
        intervals.append((start, None))
    out = []
    for a, b in intervals:
        end = b if b is not None else (truth[-1][0] if truth else a)
        walked, last = 0.0, None
        for p in truth:
            if a <= p[0] <= end:
                if last:
                    walked += math.hypot(p[1] - last[1], p[2] - last[2])
                last = p
        out.append((a, b, walked))
    return out


def score(out, truth, log_end_s):
    """The run in `out` against `truth` (list of TUM poses)."""
    estimate = read_tum(out / "trajectory.tum")
    pairs = match(estimate, truth)
    errors = [math.hypot(e[1] - t[1], e[2] - t[2]) for e, t in pairs]
    wrong_s = 0.0
    for k in range(1, len(pairs)):
        if errors[k] > WRONG_M:
            wrong_s += pairs[k][0][0] - pairs[k - 1][0][0]
    lost = lost_intervals(out / "status.csv", truth, "lost")
    lost_s = sum((b if b is not None else log_end_s) - a for a, b, _ in lost)
    outside = lost_intervals(out / "status.csv", truth, "outside")
    outside_s = sum((b if b is not None else log_end_s) - a for a, b, _ in outside)
    summary = json.loads((out / "summary.json").read_text())
    g = summary.get("global")
    anchor_s = (g["stamp"] - truth[0][0]) if g else None
    return {"errors": errors, "matched": len(pairs), "scans": summary["scans"], "wall_s": summary["processing_wall_s"],
            "lost_s": lost_s, "lost": lost, "outside_s": outside_s, "wrong_s": wrong_s, "anchor_s": anchor_s,
            "anchored": bool(estimate)}


def localise(pena, log, lines, out, mode, start, extra):
    out.mkdir(parents=True, exist_ok=True)
    cmd = [pena, "localise", "--quiet", "--log", log, "--map", lines, "--out", out]
    cmd += ["--global"] if mode == "global" else ["--start", start]
    run(cmd + list(extra), out / "run.log", out / "summary.json")


def start_arg(pose):
    return f"{pose[1]:.6f},{pose[2]:.6f},{math.degrees(pose[3]):.6f}"


def build_map(pena, name, corrected, work):
    out = work / name / "map"
    out.mkdir(parents=True, exist_ok=True)
    run([pena, "map", "--quiet", "--log", corrected, "--out", out], out / "run.log", out / "lines.csv")
    truth = out / "corrected.tum"
    run([pena, "export", "--log", corrected, "--tum", truth], out / "export.log", truth)
    return out / "lines.csv", read_tum(truth)


def perturbed_run(pena, name, corrected, lines, seed, modes, work, extra):
    out = work / name / f"seed-{seed}"
    out.mkdir(parents=True, exist_ok=True)
    log = out / "perturbed.clf"
    truth_path = out / "truth.tum"
    run([pena, "export", "--log", corrected, "--carmen", log, "--perturb-odometry", seed, "--tum", truth_path],
        out / "export.log", truth_path)
    truth = read_tum(truth_path)
    results = {}
    for mode in modes:
        localise(pena, log, lines, out / mode, mode, start_arg(truth[0]), extra)
        results[mode] = score(out / mode, truth, truth[-1][0])
    return results


def raw_run(pena, name, log, lines, truth, modes, work, extra):
    """A raw log of the same run as `truth` (the corrected poses), localised as it is."""
    out = work / name / "raw"
    out.mkdir(parents=True, exist_ok=True)
    first = out / "first.tum"
    run([pena, "export", "--log", log, "--tum", first], out / "export.log")
    stamps = read_tum(first)
    pairs = match(stamps[:1], truth)
    if not pairs:
        raise RuntimeError(f"{log}: its first scan's stamp ({stamps[0][0] if stamps else 'none'}) is not in "
                           f"the corrected log's stamps; no known start")
    results = {}
    for mode in modes:
        localise(pena, log, lines, out / mode, mode, start_arg(pairs[0][1]), extra)
        results[mode] = score(out / mode, truth, truth[-1][0])
    return results


def freiburg_truth(corrected, log, path):
    """The corrected poses at the Freiburg log's stamps (scans paired by identical ranges), in the
    corrected frame, written to `path` as TUM; returns them."""
    if not (RESUME and path.exists()):
        fit = radish_frame_fit()
        stamp_of = {}
        for key, stamp, _ in fit.scans(str(log)):
            stamp_of.setdefault(key, stamp)
        paired = sorted((stamp_of[key], pose) for key, _, pose in fit.scans(str(corrected)) if key in stamp_of)
        if len(paired) < 2:
            raise RuntimeError(f"{corrected}: only {len(paired)} scans pair with {log}; no truth")
        with open(path, "w") as out:
            for stamp, (x, y, heading) in paired:
                out.write(f"{stamp:.6f} {x:.6f} {y:.6f} 0 0 0 {math.sin(heading / 2):.9f} {math.cos(heading / 2):.9f}\n")
    return read_tum(path)


def frame_check(estimate_path, truth):
    """The rigid fit corrected_from_map of the trajectory onto the corrected poses (x m, y m,
    theta deg): near zero when the map frame is the corrected frame."""
    pairs = match(read_tum(estimate_path), truth)
    if len(pairs) < 3:
        return None
    th, tx, ty = radish_frame_fit().fit_rigid([(t[1:], e[1:]) for e, t in pairs])
    return tx, ty, math.degrees(th)


def relation_error(pena, trajectory, relations):
    res = subprocess.run([str(pena), "eval", "--json", "--trajectory", trajectory, "--relations", relations],
                         capture_output=True, text=True)
    if res.returncode != 0:
        raise RuntimeError(f"pena eval failed on {trajectory}: {res.stderr}")
    r = json.loads(res.stdout)["relations"]
    return {"mean_m": r["translational_error_m"]["mean"], "p95_m": r["translational_error_spread_m"]["p95"],
            "max_m": r["translational_error_spread_m"]["max"], "used": r["used"], "skipped": r["skipped"]}


def freiburg_run(pena, name, log, relations, corrected, lines, modes, work, extra):
    """A raw Freiburg log on its radish map: relation error and error against the corrected poses."""
    out = work / name / "freiburg"
    out.mkdir(parents=True, exist_ok=True)
    truth = freiburg_truth(corrected, log, out / "truth.tum")
    results = {}
    for mode in modes:
        localise(pena, log, lines, out / mode, mode, "0,0,0", extra)
        summary = json.loads((out / mode / "summary.json").read_text())
        relation = relation_error(pena, out / mode / "trajectory.tum", relations)
        relation.update({"scans": summary["scans"], "wall_s": summary["processing_wall_s"]})
        results[mode] = {"relations": relation, "corrected": score(out / mode, truth, truth[-1][0]),
                         "frame": frame_check(out / mode / "trajectory.tum", truth)}
    return results


def fmt(value, digits=3):
    return "-" if value is None else f"{value:.{digits}f}"


def summarise(mode, runs):
    errors = [e for r in runs for e in r["errors"]]
    longest = None
    never = 0
    for r in runs:
        for a, b, walked in r["lost"]:
            if b is None:
                never += 1
            elif longest is None or b - a > longest[0]:
                longest = (b - a, walked)
    anchors = [r["anchor_s"] for r in runs if r["anchor_s"] is not None]
    walked = [w for r in runs for _, _, w in r["lost"]]
    return {"mode": mode, "runs": len(runs), "mean_m": sum(errors) / len(errors) if errors else None,
            "p95_m": percentile(errors, 0.95), "max_m": max(errors) if errors else None,
            "matched": sum(r["matched"] for r in runs), "scans": sum(r["scans"] for r in runs),
            "lost_s": sum(r["lost_s"] for r in runs) / len(runs),
            "outside_s": sum(r["outside_s"] for r in runs) / len(runs), "intervals": sum(len(r["lost"]) for r in runs),
            "reacquire_s": longest[0] if longest else None, "reacquire_m": longest[1] if longest else None,
            "never": never, "lost_max_m": max(walked) if walked else None, "wrong_s": sum(r["wrong_s"] for r in runs) / len(runs),
            "anchor_s": max(anchors) if anchors else None, "unanchored": sum(not r["anchored"] for r in runs),
            "scans_per_s": sum(r["scans"] for r in runs) / max(1e-9, sum(r["wall_s"] for r in runs))}


def print_building(name, rows):
    print(f"\n{name}")
    print(f"  {'mode':<16} {'runs':>4} {'mean m':>7} {'p95 m':>7} {'max m':>7} {'lost s':>7} {'lost#':>5} "
          f"{'re-acq s':>8} {'re-acq m':>8} {'outside s':>9} {'wrong s':>7} {'anchor s':>8} {'scans/s':>7}")
    for r in rows:
        if "intervals" not in r:  # a Freiburg log scored on its relations
            print(f"  {r['mode']:<16} {1:>4} {fmt(r['mean_m']):>7} {fmt(r['p95_m']):>7} {fmt(r['max_m']):>7} "
                  f"{'':>7} {'':>5} {'':>8} {'':>8} {'':>9} {'':>7} {'':>8} {fmt(r['scans'] / r['wall_s'], 0):>7}")
            continue
        reacq = "never" if r["never"] else fmt(r["reacquire_s"], 1)
        print(f"  {r['mode']:<16} {r['runs']:>4} {fmt(r['mean_m']):>7} {fmt(r['p95_m']):>7} {fmt(r['max_m']):>7} "
              f"{fmt(r['lost_s'], 1):>7} {r['intervals']:>5} {reacq:>8} {fmt(r['reacquire_m'], 1):>8} "
              f"{fmt(r['outside_s'], 1):>9} {fmt(r['wrong_s'], 1):>7} {fmt(r['anchor_s'], 1):>8} {fmt(r['scans_per_s'], 0):>7}"
              + (f"  ({r['unanchored']} never anchored)" if r["unanchored"] else ""))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--pena", help="the pena binary to run (default: BUILD/tools/pena/pena)")
    parser.add_argument("--work", default="/tmp/pena-plan-localisation")
    parser.add_argument("--buildings", default=",".join(RADISH), help="radish-corrected logs to run")
    parser.add_argument("--seeds", type=int, default=10, help="perturbation seeds per building")
    parser.add_argument("--first-seed", type=int, default=1)
    parser.add_argument("--modes", default="start,global", help="start (known start), global (--global)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--raw", action="store_true", help="also the raw Freiburg logs on their radish maps")
    parser.add_argument("--corrected", action="append", default=[], help="a log with corrected poses")
    parser.add_argument("--log", action="append", default=[], help="a raw log (with --truth)")
    parser.add_argument("--truth", action="append", default=[], help="the corrected log of a --log")
    parser.add_argument("--json", help="also write the rows to this JSON file")
    parser.add_argument("--resume", action="store_true",
                        help="keep WORK and skip the steps whose outputs are there (an interrupted run)")
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    opts = parser.parse_args(argv)
    if len(opts.log) != len(opts.truth):
        parser.error("give one --truth per --log")
    modes = [m for m in opts.modes.split(",") if m]
    if not modes or set(modes) - {"start", "global"}:
        parser.error(f"--modes: start and/or global, got '{opts.modes}'")
    if opts.seeds < 1:
        parser.error("--seeds must be >= 1")
    pena = Path(opts.pena) if opts.pena else Path(opts.build) / "tools" / "pena" / "pena"
    if not os.access(pena, os.X_OK):
        sys.exit(f"plan-localisation-benchmark: {pena} is not built (bash scripts/setup.sh)")
    data = datasets_dir()
    work = Path(opts.work)
    global RESUME
    RESUME = opts.resume
    if not opts.resume:
        shutil.rmtree(work, ignore_errors=True)

    corrected = [(n, data / "radish-corrected" / f"{n}-corrected.log.gz") for n in opts.buildings.split(",") if n]
    corrected += [(Path(c).name.split(".")[0], Path(c)) for c in opts.corrected]
    raw = [(Path(l).name.split(".")[0], Path(l), Path(t)) for l, t in zip(opts.log, opts.truth)]
    for _, path in corrected:
        if not path.exists():
            sys.exit(f"plan-localisation-benchmark: {path} does not exist")
    seeds = range(opts.first_seed, opts.first_seed + opts.seeds)

    started_s = time.time()
    tables, frames = {}, {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=opts.jobs) as pool:
        maps = {n: pool.submit(build_map, pena, n, c, work) for n, c in corrected}
        maps.update({n: pool.submit(build_map, pena, n, t, work) for n, _, t in raw})
        jobs = {n: [pool.submit(lambda n=n, c=c, s=s: perturbed_run(pena, n, c, maps[n].result()[0], s, modes,
                                                                    work, extra)) for s in seeds]
                for n, c in corrected}
        raw_jobs = {n: pool.submit(lambda n=n, l=l: raw_run(pena, n, l, *maps[n].result(), modes, work, extra))
                    for n, l, _ in raw}
        freiburg_jobs = {}
        if opts.raw:
            for log, building in RAW.items():
                corrected_log = data / "radish-corrected" / f"{building}-corrected.log.gz"
                if building not in maps:
                    maps[building] = pool.submit(build_map, pena, building, corrected_log, work)
                freiburg_jobs[log] = pool.submit(
                    lambda log=log, b=building, c=corrected_log: freiburg_run(
                        pena, log, data / "freiburg" / f"{log}.clf.gz", data / "freiburg" / f"{log}.relations", c,
                        maps[b].result()[0], modes, work, extra))
        for name, runs in jobs.items():
            results = [j.result() for j in runs]
            tables[name] = [summarise(f"perturbed {m}", [r[m] for r in results]) for m in modes]
        for name, job in raw_jobs.items():
            result = job.result()
            tables[name] = [summarise(f"raw {m}", [result[m]]) for m in modes]
        for log, job in freiburg_jobs.items():
            result = job.result()
            for m in modes:
                row = result[m]["relations"]
                row["mode"] = f"freiburg {m} relations"
                tables.setdefault(RAW[log], []).append(row)
                tables[RAW[log]].append(summarise(f"freiburg {m}", [result[m]["corrected"]]))
                frames[f"{log} {m}"] = result[m]["frame"]
    print(f"plan localisation benchmark: pena localise {' '.join(extra)}; seeds {seeds.start}-{seeds.stop - 1} "
          f"(work {work})")
    for name, rows in tables.items():
        print_building(name, rows)
    if frames:
        print()
    for run_name, frame in frames.items():
        print(f"frame check {run_name}: corrected_from_map fit " +
              ("-" if frame is None else f"x {frame[0]:.3f} m, y {frame[1]:.3f} m, theta {frame[2]:.2f} deg"))
    print_acceptance(tables)
    print(f"\nwall time {time.time() - started_s:.0f} s ({opts.jobs} jobs)")
    if opts.json:
        Path(opts.json).write_text(json.dumps(tables, indent=1))


def print_acceptance(tables):
    """The issue's bar on every perturbed row."""
    print(f"\nacceptance (perturbed: mean < {ACCEPT_MEAN_M} m, p95 < {ACCEPT_P95_M} m, every lost interval "
          f"found within {ACCEPT_LOST_M:.0f} m of travel)")
    failed = 0
    for name, rows in tables.items():
        for r in rows:
            if not r["mode"].startswith("perturbed"):
                continue
            reasons = []
            if r["mean_m"] is None or r["mean_m"] >= ACCEPT_MEAN_M:
                reasons.append(f"mean {fmt(r['mean_m'])} m")
            if r["p95_m"] is None or r["p95_m"] >= ACCEPT_P95_M:
                reasons.append(f"p95 {fmt(r['p95_m'])} m")
            if r["lost_max_m"] is not None and r["lost_max_m"] > ACCEPT_LOST_M:
                reasons.append(f"a lost interval of {r['lost_max_m']:.1f} m")
            if r["unanchored"]:
                reasons.append(f"{r['unanchored']} runs never anchored")
            open_note = f"; {r['never']} interval(s) open at the log's end" if r["never"] else ""
            print(f"  {name:<10} {r['mode']:<18} {'FAIL: ' + ', '.join(reasons) if reasons else 'pass'}"
                  f" (longest lost {fmt(r['lost_max_m'], 1)} m{open_note})")
            failed += bool(reasons)
    print(f"  {'every perturbed row passes' if not failed else f'{failed} perturbed row(s) fail'}")


if __name__ == "__main__":
    main()
