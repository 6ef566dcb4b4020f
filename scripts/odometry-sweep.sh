#!/usr/bin/env bash
# The laser odometry's accuracy table (docs/odometry.md): the three Freiburg logs (mean relation
# error, no loop closure) and simulated firefighters over several seeds (final error in % of the
# path, translation and heading RMSE), so that a regression in any of them is visible.
#
#   scripts/odometry-sweep.sh [--build DIR] [--work DIR] [--only freiburg|sim|LOGNAME|SCENARIO]
#                             [--seeds "1 2 3"] [--modes "default no-matching stride-only"]
#                             [-- extra pena odometry options, e.g. --set prior_gate_rad=0]
#
# Runs one job at a time (the whole sweep takes a few minutes on one core). Missions are
# simulated once into WORK/sim and reused. Prints one table row per run.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
work=/tmp/pena-odometry-sweep
only=all
seeds="1 2 3"
modes="default"
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "odometry-sweep: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
pena="$build/tools/pena/pena"
[[ -x "$pena" ]] || { echo "odometry-sweep: $pena not built (make -C $build pena)" >&2; exit 1; }
datasets=${PENA_DATA_DIR:-data}  # the Freiburg logs (data/README.md)
mkdir -p "$work"

# field NAME JSON: the first number after "NAME": in a one-line JSON object.
field() { sed -n "s/.*\"$1\": *{\?\"\?mean\"\?:\? *\([-0-9.e]*\).*/\1/p; t; s/.*\"$1\": *\([-0-9.e]*\).*/\1/p" <<<"$2" | head -1; }
mean_of() { sed -n "s/.*\"$1\": {\"mean\": \([-0-9.e]*\).*/\1/p" <<<"$2"; }

mode_options() {
  case "$1" in
    default) ;;
    no-matching) echo "--no-matching" ;;
    stride-only) echo "--prior stride-only" ;;
    *) echo "odometry-sweep: unknown mode '$1'" >&2; exit 2 ;;
  esac
}

run_freiburg() {
  local name=$1 log="$datasets/freiburg/$1.clf.gz" out="$work/freiburg-$1"
  "$pena" odometry --log "$log" --out "$out" --quiet "${extra[@]}" >"$out.stdout"
  local eval summary
  eval=$("$pena" eval --trajectory "$out/trajectory.tum" --relations "$datasets/freiburg/$1.relations" --json)
  summary=$(cat "$out/summary.json")
  printf '%-10s %-12s trans %8s +/- %-8s m  rot %7s deg  failed %5s gated %5s stale %4s  %6sx real time\n' \
    "$name" default "$(printf %.3f "$(mean_of translational_error_m "$eval")")" \
    "$(printf %.3f "$(sed -n 's/.*"translational_error_m": {"mean": [-0-9.e]*, "std": \([-0-9.e]*\).*/\1/p' <<<"$eval")")" \
    "$(printf %.2f "$(mean_of rotational_error_deg "$eval")")" \
    "$(field failed "$summary")" "$(field gated "$summary")" "$(field stale "$summary")" \
    "$(field speed_x_real_time "$summary")"
}

run_sim() {
  local scenario=$1 seed=$2 mode=$3 mission="$work/sim/$1-$2"
  [[ -d "$mission" ]] || "$pena" simulate --scenario "$scenario" --seed "$seed" --out "$mission" >/dev/null
  local out="$work/$scenario-$seed-$mode"
  # shellcheck disable=SC2046
  "$pena" odometry --log "$mission/ff1/sensors.penalog" --out "$out" --quiet $(mode_options "$mode") \
    "${extra[@]}" >"$out.stdout"
  local eval
  eval=$("$pena" eval --trajectory "$out/trajectory.tum" --truth "$mission/ff1/truth.tum" --json)
  printf '%-10s seed %-3s %-12s final %6s %% of %5s m  RMSE %6s m  heading %6s deg  failed %4s gated %4s\n' \
    "$scenario" "$seed" "$mode" "$(printf %.2f "$(field final_error_percent_of_path "$eval")")" \
    "$(printf %.0f "$(field truth_path_length_m "$eval")")" \
    "$(printf %.2f "$(field translation_rmse_m "$eval")")" \
    "$(printf %.2f "$(field heading_rmse_deg "$eval")")" \
    "$(field failed "$(cat "$out/summary.json")")" "$(field gated "$(cat "$out/summary.json")")"
}

for name in intel aces mit-csail; do
  [[ $only == all || $only == freiburg || $only == "$name" ]] && run_freiburg "$name"
done
for scenario in loop170 office; do
  [[ $only == all || $only == sim || $only == "$scenario" ]] || continue
  for seed in $seeds; do
    for mode in $modes; do run_sim "$scenario" "$seed" "$mode"; done
  done
done
