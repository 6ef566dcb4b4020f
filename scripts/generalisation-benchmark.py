#!/usr/bin/env python3
"""The generalisation benchmark: the per-entity chain with its defaults on every real log we have,
on real logs whose odometry is perturbed by a documented noise model, and on simulated missions;
one table (docs/evaluation.md, "Generalisation benchmark").

Rows:
  real       each Freiburg log (raw odometry) scored by its relations: mean, median, 95th
             percentile and max translational relation error, max rotational relation error.
  perturbed  each radish-corrected log, its corrected poses as odometry perturbed by
             `pena export --perturb-odometry SEED` (scale errors, heading random walk, sudden
             slips of 5-30 deg), scored against the corrected poses: per log the mean over seeds
             of the trajectory RMSE, the worst final and max heading error, runs over 5 deg.
  sim        simulated firefighters (loop170, office) scored against their truth: RMSE and final
             error in % of the path.
Every row also gives `jump`: the largest turn one scan's match gave the heading away from its
motion prior (degrees; worst over seeds): a slip caught, or a wrong match taken.
Logs nobody here has seen are scored the same way: --log LOG --relations R (a real log with
Kuemmerle relations) or --corrected LOG (a log with corrected poses, perturbed like the radish ones).

  scripts/generalisation-benchmark.py [--build DIR] [--work DIR] [--sets real,perturbed,sim]
      [--seeds N] [--sim-seeds N] [--jobs N] [--slam] [--log LOG --relations R]...
      [--corrected LOG]... [-- extra pena odometry/map options]

--slam runs `pena map` (keyframe SLAM) instead of `pena odometry` on the real and perturbed logs.
--jobs N runs N chains at once (default 2); each chain uses one core. Wall times are per run.
"""
import argparse
import csv
import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FREIBURG = ["intel", "aces", "mit-csail", "fr-clinic"]
RADISH = ["intel", "aces", "csail", "seattle", "orebro"]
SIM = ["loop170", "office"]


def datasets_dir():
    env = os.environ.get("PENA_DATASETS")
    if env:
        return Path(env)
    for candidate in (ROOT / "data", ROOT.parent / "shared" / "datasets"):
        if (candidate / "freiburg").is_dir():
            return candidate
    sys.exit("generalisation-benchmark: no datasets found (set PENA_DATASETS)")


def run(cmd, log_path):
    with open(log_path, "w") as log:
        result = subprocess.run([str(c) for c in cmd], stdout=log, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed (exit {result.returncode}); see {log_path}")


def eval_json(pena, args, log_path):
    out = subprocess.run([str(pena), "eval", "--json", *map(str, args)], capture_output=True, text=True)
    if out.returncode != 0:
        Path(log_path).write_text(out.stdout + out.stderr)
        raise RuntimeError(f"pena eval failed; see {log_path}")
    return json.loads(out.stdout)


def largest_jump_deg(out):
    """The largest turn one scan's match gave the heading away from its motion prior (degrees):
    a slip caught, or a wrong match taken (DIR/odometry.csv; None without it)."""
    path = out / "odometry.csv"
    if not path.exists():
        return None
    jump = 0.0
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["status"] in ("matched", "degenerate"):
                turn = float(row["theta"]) - float(row["prior_theta"])
                jump = max(jump, abs(math.degrees(math.atan2(math.sin(turn), math.cos(turn)))))
    return jump


def worst(values):
    values = [v for v in values if v is not None]
    return max(values) if values else None


def chain(pena, log, out, opts, extra):
    """Runs the chain on `log` into `out`; returns (trajectory path, wall seconds, log seconds)."""
    out.mkdir(parents=True, exist_ok=True)
    if opts.slam:
        cmd = [pena, "map", "--quiet", "--log", log, "--out", out, "--slam", *extra]
    else:
        cmd = [pena, "odometry", "--quiet", "--log", log, "--out", out, *extra]
    run(cmd, out / "run.log")
    wall_s = log_s = None
    summary = out / "summary.json"
    if summary.exists():
        s = json.loads(summary.read_text())
        wall_s = s.get("processing_wall_s")
        log_s = s.get("log_duration_s")
    return out / "trajectory.tum", wall_s, log_s


def real_row(pena, name, log, relations, work, opts, extra):
    out = work / "real" / name
    traj, wall_s, log_s = chain(pena, log, out, opts, extra)
    r = eval_json(pena, ["--trajectory", traj, "--relations", relations], out / "eval.log")["relations"]
    t, s, rot = r["translational_error_m"], r["translational_error_spread_m"], r["rotational_error_spread_deg"]
    return {"set": "real", "log": name, "mean_m": t["mean"], "median_m": s["median"], "p95_m": s["p95"],
            "max_m": s["max"], "max_rot_deg": rot["max"], "jump_deg": largest_jump_deg(out),
            "wall_s": wall_s, "log_s": log_s}


def perturbed_run(pena, name, corrected, seed, work, opts, extra):
    out = work / "perturbed" / f"{name}-{seed}"
    out.mkdir(parents=True, exist_ok=True)
    log = out / "perturbed.clf"
    truth = out / "truth.tum"
    run([pena, "export", "--log", corrected, "--carmen", log, "--perturb-odometry", seed,
         "--tum", truth], out / "export.log")
    traj, wall_s, log_s = chain(pena, log, out / "run", opts, extra)
    t = eval_json(pena, ["--trajectory", traj, "--truth", truth], out / "eval.log")["truth"]
    return {"rmse_m": t["translation_rmse_m"], "max_m": t["max_translation_error_m"],
            "final_heading_deg": t["final_heading_error_deg"], "max_heading_deg": t["max_heading_error_deg"],
            "jump_deg": largest_jump_deg(out / "run"), "wall_s": wall_s, "log_s": log_s}


def perturbed_row(name, runs, seeds):
    n = len(runs)
    return {"set": f"perturbed x{seeds}", "log": name,
            "mean_m": sum(r["rmse_m"] for r in runs) / n,
            "median_m": sorted(r["rmse_m"] for r in runs)[(n - 1) // 2],
            "p95_m": None, "max_m": max(r["max_m"] for r in runs),
            "max_rot_deg": max(r["max_heading_deg"] for r in runs),
            "final_heading_worst_deg": max(r["final_heading_deg"] for r in runs),
            "runs_over_5deg": sum(r["final_heading_deg"] > 5.0 for r in runs),
            "jump_deg": worst(r["jump_deg"] for r in runs),
            "wall_s": sum(r["wall_s"] or 0 for r in runs), "log_s": sum(r["log_s"] or 0 for r in runs)}


def sim_run(pena, scenario, seed, work, extra):
    out = work / "sim" / f"{scenario}-{seed}"
    mission = out / "mission"
    if not (mission / "ff1" / "truth.tum").exists():
        out.mkdir(parents=True, exist_ok=True)
        run([pena, "simulate", "--scenario", scenario, "--seed", seed, "--out", mission], out / "simulate.log")
    traj, wall_s, log_s = chain(pena, mission / "ff1" / "sensors.penalog", out / "run",
                                argparse.Namespace(slam=False), extra)
    t = eval_json(pena, ["--trajectory", traj, "--truth", mission / "ff1" / "truth.tum"], out / "eval.log")["truth"]
    return {"rmse_m": t["translation_rmse_m"], "final_pct": t["final_error_percent_of_path"],
            "max_m": t["max_translation_error_m"], "max_heading_deg": t["max_heading_error_deg"],
            "jump_deg": largest_jump_deg(out / "run"), "wall_s": wall_s, "log_s": log_s}


def sim_row(scenario, runs):
    n = len(runs)
    return {"set": f"sim x{n}", "log": scenario, "mean_m": sum(r["rmse_m"] for r in runs) / n,
            "median_m": sorted(r["rmse_m"] for r in runs)[(n - 1) // 2], "p95_m": None,
            "max_m": max(r["max_m"] for r in runs), "max_rot_deg": max(r["max_heading_deg"] for r in runs),
            "final_pct_worst": max(r["final_pct"] for r in runs),
            "jump_deg": worst(r["jump_deg"] for r in runs),
            "wall_s": sum(r["wall_s"] or 0 for r in runs), "log_s": sum(r["log_s"] or 0 for r in runs)}


def fmt(value, digits=3):
    return "-" if value is None else f"{value:.{digits}f}"


def print_table(rows):
    print(f"{'set':<14} {'log':<16} {'mean m':>8} {'median':>8} {'p95':>8} {'max m':>8} "
          f"{'max rot':>8} {'jump':>6} {'extra':<22} {'wall s':>8} {'x real':>7}")
    for r in rows:
        if "runs_over_5deg" in r:
            extra = f"final hdg<={r['final_heading_worst_deg']:.1f}deg,{r['runs_over_5deg']}>5"
        elif "final_pct_worst" in r:
            extra = f"final<={r['final_pct_worst']:.2f}% path"
        else:
            extra = ""
        speed = r["log_s"] / r["wall_s"] if r.get("wall_s") and r.get("log_s") else None
        print(f"{r['set']:<14} {r['log']:<16} {fmt(r['mean_m']):>8} {fmt(r['median_m']):>8} "
              f"{fmt(r['p95_m']):>8} {fmt(r['max_m']):>8} {fmt(r['max_rot_deg'], 1):>8} "
              f"{fmt(r.get('jump_deg'), 1):>6} {extra:<22} "
              f"{fmt(r['wall_s'], 1):>8} {fmt(speed, 0):>7}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--pena", help="the pena binary to run (default: BUILD/tools/pena/pena)")
    parser.add_argument("--work", default="/tmp/pena-generalisation")
    parser.add_argument("--sets", default="real,perturbed,sim")
    parser.add_argument("--seeds", type=int, default=10, help="perturbation seeds per radish log")
    parser.add_argument("--sim-seeds", type=int, default=5, help="seeds per simulated scenario")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--slam", action="store_true")
    parser.add_argument("--freiburg", default=",".join(FREIBURG), help="Freiburg logs to run")
    parser.add_argument("--radish", default=",".join(RADISH), help="radish-corrected logs to run")
    parser.add_argument("--log", action="append", default=[], help="a real CARMEN log (with --relations)")
    parser.add_argument("--relations", action="append", default=[])
    parser.add_argument("--corrected", action="append", default=[], help="a log with corrected poses")
    parser.add_argument("--json", help="also write the rows to this JSON file")
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    opts = parser.parse_args(argv)
    if len(opts.log) != len(opts.relations):
        parser.error("give one --relations per --log")
    pena = Path(opts.pena) if opts.pena else Path(opts.build) / "tools" / "pena" / "pena"
    if not os.access(pena, os.X_OK):
        sys.exit(f"generalisation-benchmark: {pena} is not built (bash scripts/setup.sh)")
    sets = set(opts.sets.split(","))
    unknown = sets - {"real", "perturbed", "sim"}
    if unknown:
        parser.error(f"unknown set(s) {','.join(sorted(unknown))}: real, perturbed, sim")
    work = Path(opts.work)
    data = datasets_dir()
    shutil.rmtree(work / "real", ignore_errors=True)
    shutil.rmtree(work / "perturbed", ignore_errors=True)

    real = []
    if "real" in sets:
        real = [(n, data / "freiburg" / f"{n}.clf.gz", data / "freiburg" / f"{n}.relations")
                for n in opts.freiburg.split(",") if n]
    real += [(Path(l).name.split(".")[0], Path(l), Path(r)) for l, r in zip(opts.log, opts.relations)]
    corrected = []
    if "perturbed" in sets:
        corrected = [(n, data / "radish-corrected" / f"{n}-corrected.log.gz") for n in opts.radish.split(",") if n]
    corrected += [(Path(c).name.split(".")[0], Path(c)) for c in opts.corrected]

    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=opts.jobs) as pool:
        real_jobs = [pool.submit(real_row, pena, n, l, r, work, opts, extra) for n, l, r in real]
        pert_jobs = {n: [pool.submit(perturbed_run, pena, n, c, s, work, opts, extra)
                         for s in range(1, opts.seeds + 1)] for n, c in corrected}
        sim_jobs = {}
        if "sim" in sets:
            sim_jobs = {sc: [pool.submit(sim_run, pena, sc, s, work, extra)
                             for s in range(1, opts.sim_seeds + 1)] for sc in SIM}
        for job in real_jobs:
            rows.append(job.result())
        for name, jobs in pert_jobs.items():
            rows.append(perturbed_row(name, [j.result() for j in jobs], opts.seeds))
        for scenario, jobs in sim_jobs.items():
            rows.append(sim_row(scenario, [j.result() for j in jobs]))
    mode = "pena map --slam" if opts.slam else "pena odometry"
    print(f"generalisation benchmark: {mode} {' '.join(extra)} (work {work})")
    print_table(rows)
    if opts.json:
        Path(opts.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
