#!/usr/bin/env python3
"""The generated part of docs/link-experiments.md from a link-experiments.sh output directory.

  report.py --out OUT --build BUILD --images DIR --command CMD > report.md
      tables, acceptance, bytes, grids against line maps; plots DIR/link-*.png (pena-link-plot)
  report.py --splice docs/link-experiments.md < report.md
      replaces the text between the GENERATED markers of that file
"""
import argparse
import csv
import glob
import json
import os
import subprocess
import sys

BEGIN, END = "<!-- BEGIN GENERATED (scripts/link-experiments.sh) -->", "<!-- END GENERATED -->"


def splice(path):
    text, new = open(path).read(), sys.stdin.read()
    start, stop = text.index(BEGIN) + len(BEGIN), text.index(END)
    open(path, "w").write(text[:start] + "\n" + new.rstrip() + "\n" + text[stop:])


def fmt(x, spec=".2f"):
    return "n/a" if x is None else format(x, spec)


def load_results(out, build):
    """Re-analyses every finished run (analyse-run.py of this tree) and loads its result."""
    here = os.path.dirname(os.path.abspath(__file__))
    for run in sorted(glob.glob(f"{out}/runs/*/times.json")):
        run = os.path.dirname(run)
        res = subprocess.run([sys.executable, f"{here}/analyse-run.py", run,
                              f"{build}/services/monitor/pena-monitor"], capture_output=True, text=True)
        if res.returncode == 0:
            open(f"{run}/result.json", "w").write(res.stdout)
    results = {}
    for path in sorted(glob.glob(f"{out}/runs/*/result.json")):
        try:
            results[os.path.basename(os.path.dirname(path))] = json.load(open(path))
        except ValueError:
            pass
    return results


def table(results):
    lines = ["| run | kbit/s | pose age p50 / p99 / max (s) | p99 outside outage (s) | poses delivered | "
             "longest pose gap (s) | map at post = fusion's | converged after last change (s) | "
             "versions not applied by delta at the post by the end / snapshots used | link bit/s to post |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in sorted(results.items(), key=lambda kv: (kv[1]["rate_kbit"], kv[0])):
        lines.append(
            f"| {name} | {r['rate_kbit']} | {fmt(r['pose_age_p50_s'])} / {fmt(r['pose_age_p99_s'])} / "
            f"{fmt(r['pose_age_max_s'])} | {fmt(r['pose_age_p99_outside_outage_s'])} | "
            f"{fmt(r['pose_delivery'], '.1%') if r['pose_delivery'] is not None else 'n/a'} | "
            f"{fmt(r['longest_pose_gap_s'], '.1f')} | {r['post_map_equals_fusion']} | "
            f"{fmt(r['map_converged_after_last_change_s'], '.1f')} | "
            f"{r['map_deltas_missing_at_post']} of {r['map_versions_published']} / {r['post_snapshots_used']} | "
            f"{fmt(r['link_to_post_bit_s'], '.0f')} |")
    return lines


def acceptance_of(name, r):
    p99, conv = r["pose_age_p99_s"], r["map_converged_after_last_change_s"]
    no_loss = r["post_map_equals_fusion"] and r["map_deltas_missing_at_post"] == 0
    ok = lambda b: "**met**" if b else "**NOT met**"
    return [f"`{name}` ({r['outage'] or 'no'} s outage after the entities started, mission at "
            f"{r['entity_rate']}x real time):", "",
            f"- pose age p99 at the command post: {fmt(p99)} s (< 2 s: {ok(p99 is not None and p99 < 2.0)});",
            f"- global map converged {fmt(conv, '.1f')} s after its last change "
            f"(< 60 s: {ok(conv is not None and conv < 60.0)});",
            f"- map deltas through the outage: {r['map_deltas_missing_at_post']} of "
            f"{r['map_versions_published']} versions not applied by delta at the post by the end of the run (lost, skipped by a "
            f"snapshot or still queued), post map equals "
            f"fusion's final map: {r['post_map_equals_fusion']} ({ok(no_loss)}).", ""]


def acceptance(results):
    lines = []
    names = [n for n in sorted(results) if n.startswith("gateway") and n.endswith("-9.6")]
    if not names:
        lines += ["No gateway run at 9.6 kbit/s in this output: acceptance not measured.", ""]
    for name in names:
        lines += acceptance_of(name, results[name])
    variants = sorted({n.rsplit("-", 1)[0] for n in results if not n.endswith("-lossy")})
    lines += ["Pose age p99 over the poses received at the post (s), per variant:", "",
              "| kbit/s | " + " | ".join(variants) + " |", "|---|" + "---|" * len(variants)]
    for rate in sorted({x["rate_kbit"] for x in results.values()}):
        cells = []
        for v in variants:
            r = results.get(f"{v}-{rate:g}")
            cells.append(fmt(r["pose_age_p99_s"]) if r else "")
        lines.append(f"| {rate:g} | " + " | ".join(cells) + " |")
    return lines


def bytes_section(results):
    lines = ["| run | reached the post (bytes) | offered toward the post | reached the building | offered toward the building "
             "| by class (bytes, building -> post) |", "|---|---|---|---|---|---|"]
    for name, r in sorted(results.items(), key=lambda kv: (kv[1]["rate_kbit"], kv[0])):
        link = r.get("link", {})
        classes = ", ".join(f"{k} {v}" for k, v in sorted(r.get("bytes_by_class", {}).items()))
        lines.append(f"| {name} | {link.get('to_post_bytes', 'n/a')} | {link.get('offered_by_building_bytes', 'n/a')} "
                     f"| {link.get('to_building_bytes', 'n/a')} | {link.get('offered_by_post_bytes', 'n/a')} "
                     f"| {classes or 'n/a'} |")
    return lines


def grid_section(out, build, results):
    run = next((f"{out}/runs/{n}" for n in ("gateway-9.6", "dds-9.6") + tuple(results) if
                os.path.isdir(f"{out}/runs/{n}/entities")), None)
    if run is None:
        return ["No run with entity trajectories: grids not measured."]
    traffic = {}
    try:
        for row in csv.DictReader(open(f"{run}/fusion/traffic.csv")):
            if row["direction"] == "received" and row["topic"].endswith("line_map_delta"):
                traffic[row["entity"]] = (int(row["samples"]), int(row["bytes"]))
    except OSError:
        pass
    lines = [f"Grids rebuilt from each entity's log at the poses it published in `{os.path.basename(run)}` "
             "(pena-link-gridcost, 5 cm cells, one update per mission second in which the grid changed), "
             "against the line-map deltas pena-fusion received from it in that run (serialised DDS payload):",
             "", "| entity | grid updates | whole grid PNG per update, total (bytes) | changed box PNG, total (bytes) | "
             "line-map deltas (samples, bytes) | changed-box grid / line deltas |", "|---|---|---|---|---|---|"]
    for entity_dir in sorted(glob.glob(f"{out}/mission/*/sensors.penalog")):
        entity = os.path.basename(os.path.dirname(entity_dir))
        trajectory = f"{run}/entities/{entity}/trajectory.tum"
        if not os.path.exists(trajectory):
            continue
        res = subprocess.run([f"{build}/services/monitor/pena-link-gridcost", "--log", entity_dir,
                              "--trajectory", trajectory], capture_output=True, text=True)
        if res.returncode != 0:
            lines.append(f"| {entity} | failed: {res.stderr.strip()} | | | | |"); continue
        g = json.loads(res.stdout)
        samples, nbytes = traffic.get(entity, (0, 0))
        ratio = f"{g['changed_png_bytes_total'] / nbytes:.1f}x" if nbytes else "n/a"
        lines.append(f"| {entity} | {g['updates']} | {g['full_png_bytes_total']} | {g['changed_png_bytes_total']} "
                     f"| {samples}, {nbytes} | {ratio} |")
    return lines


def plots(out, build, images, results):
    lines = []
    rates = sorted({r["rate_kbit"] for r in results.values()})
    for rate in rates:
        tag = f"{rate:g}".replace(".", "k")
        age_csv, map_csv = f"{out}/plot-age-{tag}.csv", f"{out}/plot-map-{tag}.csv"
        with open(age_csv, "w") as age_f, open(map_csv, "w") as map_f:
            age_f.write("series,x,y\n"); map_f.write("series,x,y\n")
            wrote_building = False
            for name, r in sorted(results.items()):
                if r["rate_kbit"] != rate:
                    continue
                for row in csv.DictReader(open(f"{out}/runs/{name}/series-age.csv")):
                    age_f.write(f"{name},{row['t_s']},{row['age_s']}\n")
                for row in csv.DictReader(open(f"{out}/runs/{name}/series-map.csv")):
                    if row["side"] == "post":
                        map_f.write(f"{name} (post),{row['t_s']},{row['fraction']}\n")
                    elif not wrote_building:
                        map_f.write(f"fusion ({name}),{row['t_s']},{row['fraction']}\n")
                wrote_building = True
        for kind, csv_path, ylabel, extra in (
                ("pose-age", age_csv, "pose age at the post (s), clipped at 10", ["--points", "--ymax", "10"]),
                ("map", map_csv, "global map version / final version", ["--ymax", "1.05"])):
            png = f"{images}/link-{kind}-{tag}.png"
            subprocess.run([f"{build}/services/monitor/pena-link-plot", "--in", csv_path, "--out", png,
                            "--title", f"{kind.replace('-', ' ')} over time, {rate:g} kbit/s (s since the entities started)",
                            "--xlabel", "time (s)", "--ylabel", ylabel] + extra, check=True)
            lines.append(f"![{kind} {rate:g} kbit/s](images/link-{kind}-{tag}.png)")
    return lines


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--splice")
    parser.add_argument("--out"); parser.add_argument("--build"); parser.add_argument("--images")
    parser.add_argument("--command", default="scripts/link-experiments.sh")
    a = parser.parse_args()
    if a.splice:
        splice(a.splice); return
    os.makedirs(a.images, exist_ok=True)
    results = load_results(a.out, a.build)
    doc = [f"Generated by `sudo {a.command}` (output {a.out}).", "", "### Results", ""]
    doc += table(results) + ["", "### Acceptance", ""] + acceptance(results)
    doc += ["", "### Bytes on the link", ""] + bytes_section(results)
    doc += ["", "### Line maps against grids", ""] + grid_section(a.out, a.build, results)
    doc += ["", "### Plots", ""] + plots(a.out, a.build, a.images, results)
    print("\n".join(doc))


main()
