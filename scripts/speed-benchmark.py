#!/usr/bin/env python3
"""Where the time goes: `pena odometry` and `pena map --ignore-logged-poses` with defaults on the
shared Freiburg logs and one simulated firefighter, pinned to one core.

For each log it prints the speed (log seconds per wall second, "x real time"), the peak resident
memory and the per-stage table from summary.json (`stage_times`): seconds, % of the run's wall
time and calls. Figures are printed, never asserted: on a shared machine they move from run to
run, so compare ratios within one run. docs/odometry.md, "Where the time goes".

    scripts/speed-benchmark.py [--pena build/tools/pena/pena] [--out /tmp/pena-speed] [--cpu 1]
                               [--with-fr-clinic] [--only intel,office] [--no-map] [--markdown]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FREIBURG = ["intel", "aces", "mit-csail"]
SLOW = ["fr-clinic"]  # ~10 min and 2 GB for pena map: --with-fr-clinic
SIMULATED = "office"  # pena simulate --scenario office --seed 2, firefighter ff1


def run(command, cpu):
    pinned = (["taskset", "-c", str(cpu)] if cpu >= 0 and shutil.which("taskset") else []) + command
    result = subprocess.run(pinned, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        sys.exit("failed: " + " ".join(pinned) + "\n" + result.stderr)


def read_summary(directory):
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)


def stage_rows(times, prefix, skip=()):
    """(name, seconds, calls) of a chain's stages (without its total)."""
    return [(prefix + name, t["s"], t["calls"])
            for name, t in times.items() if name != "total" and name not in skip]


def odometry_rows(summary):
    """The odometry run's wall time split into stages; the rows sum to processing_wall_s."""
    stages = summary["stage_times"]
    pipeline = stages["pipeline"]
    rows = stage_rows(stages["odometry"], "odometry.")
    rows += stage_rows(pipeline, "pipeline.", skip=("odometry",))
    rows.append(("adapter (log reading, outputs)",
                 summary["processing_wall_s"] - pipeline["total"]["s"], 1))
    return rows, summary["processing_wall_s"]


def map_rows(summary):
    """The map run's wall time split into stages; the rows sum to total_wall_s."""
    stages = summary.get("stage_times", {})
    rows = []
    if "odometry" in stages:
        rows += stage_rows(stages["odometry"], "odometry.")
    if "slam" in stages:
        rows += stage_rows(stages["slam"], "slam.")
    if "pipeline" in stages:
        pipeline = stages["pipeline"]
        rows += stage_rows(pipeline, "pipeline.", skip=("odometry", "slam"))
        rows.append(("adapter (SLAM pass: log reading, outputs)",
                     summary["slam_wall_s"] - pipeline["total"]["s"], 1))
    rows.append(("map: grid pass (log read again, grid insertion)", summary["grid_wall_s"], 1))
    rows.append(("map: line extraction", summary["extract_s"], 1))
    rows.append(("map: writing", summary["write_s"], 1))
    accounted = summary["slam_wall_s"] + summary["grid_wall_s"] + summary["extract_s"] + summary["write_s"]
    rows.append(("map: rest", summary["total_wall_s"] - accounted, 1))
    return rows, summary["total_wall_s"]


def print_table(title, summary, rows, total_s):
    speed = summary["speed_x_real_time"]
    print(f"\n{title}: {speed:.1f} x real time ({summary['log_duration_s']:.0f} s of log in "
          f"{total_s:.2f} s), peak {summary['peak_rss_mb']:.0f} MB")
    print(f"  {'stage':<48} {'seconds':>9} {'%':>6} {'calls':>9}")
    for name, seconds, calls in rows:
        if abs(seconds) < 0.0005 and calls <= 1:
            continue
        share = 100.0 * seconds / total_s if total_s > 0 else 0.0
        print(f"  {name:<48} {seconds:9.3f} {share:6.1f} {calls:9d}")
    print(f"  {'total':<48} {total_s:9.3f} {100.0:6.1f}")


def markdown(results):
    """One table: the stages as rows, the runs as columns (seconds and %)."""
    names = []
    for _, rows, _, _ in results:
        for name, seconds, calls in rows:
            if name not in names and (abs(seconds) >= 0.0005 or calls > 1):
                names.append(name)
    print("\n| stage | " + " | ".join(title for title, _, _, _ in results) + " |")
    print("|---|" + "---:|" * len(results))
    for name in names:
        cells = []
        for _, rows, total_s, _ in results:
            found = [r for r in rows if r[0] == name]
            cells.append(f"{found[0][1]:.2f} s ({100.0 * found[0][1] / total_s:.1f} %)" if found else "")
        print(f"| {name} | " + " | ".join(cells) + " |")
    print("| **wall time** | " + " | ".join(f"{t:.2f} s" for _, _, t, _ in results) + " |")
    print("| x real time, peak memory | " +
          " | ".join(f"{s['speed_x_real_time']:.1f}x, {s['peak_rss_mb']:.0f} MB" for _, _, _, s in results) + " |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pena", default=os.path.join(ROOT, "build", "tools", "pena", "pena"))
    parser.add_argument("--out", default="/tmp/pena-speed")
    parser.add_argument("--cpu", type=int, default=1, help="core to pin to (taskset); -1: no pinning")
    parser.add_argument("--with-fr-clinic", action="store_true", help="fr-clinic too (slow)")
    parser.add_argument("--only", default="", help="comma-separated names (intel, aces, mit-csail, fr-clinic, office)")
    parser.add_argument("--no-map", action="store_true", help="pena odometry only")
    parser.add_argument("--markdown", action="store_true", help="also one markdown table of all runs")
    args = parser.parse_args()

    names = FREIBURG + (SLOW if args.with_fr_clinic else []) + [SIMULATED]
    if args.only:
        names = [n for n in args.only.split(",") if n]
    os.makedirs(args.out, exist_ok=True)
    results = []
    for name in names:
        if name == SIMULATED:
            mission = os.path.join(args.out, "office-2")
            run([args.pena, "simulate", "--scenario", "office", "--seed", "2", "--out", mission], -1)
            log, title = os.path.join(mission, "ff1", "sensors.penalog"), "office seed 2 ff1"
        else:
            log, title = os.path.join(ROOT, "data", "freiburg", name + ".clf.gz"), name
            if not os.path.exists(log):
                sys.exit(f"{log}: missing (data/freiburg holds the shared logs)")
        out = os.path.join(args.out, name)
        run([args.pena, "odometry", "--log", log, "--out", out + "-odometry", "--quiet"], args.cpu)
        summary = read_summary(out + "-odometry")
        rows, total_s = odometry_rows(summary)
        print_table(f"{title}, pena odometry", summary, rows, total_s)
        results.append((f"{title} odometry", rows, total_s, summary))
        if args.no_map:
            continue
        run([args.pena, "map", "--log", log, "--out", out + "-map", "--ignore-logged-poses", "--quiet"],
            args.cpu)
        summary = read_summary(out + "-map")
        rows, total_s = map_rows(summary)
        print_table(f"{title}, pena map --ignore-logged-poses", summary, rows, total_s)
        results.append((f"{title} map", rows, total_s, summary))
    if args.markdown:
        markdown(results)


if __name__ == "__main__":
    main()
