#!/usr/bin/env bash
# The mapping figure from odometry poses over many simulated missions: each office and
# loop170 seed is simulated (once; kept in the work directory), mapped with `pena map` (odometry
# + SLAM unless the extra options say otherwise) and scored with `pena eval --lines` against the
# walls its laser saw. Prints each mission's coverage, precision, fragmentation and trajectory RMSE
# (against truth.tum; coverage follows it, docs/slam.md), and the means over office,
# loop170, the headline set (both scenarios, seeds 1-8) and all. `--aligned` adds the
# coverage left once the map is moved by the rigid fit of its trajectory onto the truth
# (scripts/aligned-line-map.py): the map's own inconsistency, without the shift.
# Single maps are chaotic (a change that leaves the 30-map mean within a point moves single maps
# by up to 60 points, docs/slam.md), so compare variants on the means.
#
#   scripts/map-coverage.sh [--build DIR] [--work DIR] [--office "1 2 ..."] [--loop "1 2 ..."]
#                           [--jobs N] [--aligned] [--laps N] [-- extra pena map options,
#                           e.g. --no-slam or --set slam.loop_window_m=0.3]
# Defaults: office seeds 1-19, loop170 seeds 1-11, two maps at a time, work dir
# /tmp/pena-map-coverage (missions in WORK/missions, maps in WORK/maps). About 2 minutes on two
# cores once the missions exist. `--laps N` walks every route N times (`pena simulate --laps`); the
# work dir then defaults to /tmp/pena-map-coverage-lapsN (docs/slam.md).
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
work=
laps=1
office_seeds=$(seq -s ' ' 1 19)
loop_seeds=$(seq -s ' ' 1 11)
jobs=2
aligned=0
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --office) office_seeds=$2; shift 2 ;;
    --loop) loop_seeds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --aligned) aligned=1; shift ;;
    --laps) laps=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "map-coverage: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
pena="$build/tools/pena/pena"
[[ -x "$pena" ]] || { echo "map-coverage: $pena not built" >&2; exit 1; }
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "map-coverage: --jobs must be a positive integer, not '$jobs'" >&2; exit 2; }
[[ "$laps" =~ ^[1-9][0-9]*$ ]] || { echo "map-coverage: --laps must be a positive integer, not '$laps'" >&2; exit 2; }
if [[ -z "$work" ]]; then
  work=/tmp/pena-map-coverage
  ((laps > 1)) && work="$work-laps$laps"
fi
for seed in $office_seeds $loop_seeds; do
  [[ "$seed" =~ ^[0-9]+$ ]] || { echo "map-coverage: seeds must be integers, not '$seed'" >&2; exit 2; }
done

missions=()
for seed in $office_seeds; do missions+=("office $seed"); done
for seed in $loop_seeds; do missions+=("loop170 $seed"); done
mkdir -p "$work/missions" "$work/maps"

# Simulates one mission if it is not there yet (the simulator is deterministic per seed). DIR/laps
# records the laps walked (missing: 1, as written before --laps), so that a work directory's
# missions are never scored as another lap count's.
simulate() {
  local scenario=$1 seed=$2 dir="$work/missions/$1-$2"
  if [[ -f "$dir/observed.csv" ]]; then
    local had=1
    [[ -f "$dir/laps" ]] && had=$(< "$dir/laps")
    [[ "$had" == "$laps" ]] && return 0
    echo "map-coverage: $dir was simulated with $had lap(s), not $laps: use another --work" >&2
    return 1
  fi
  local lap_option=()
  ((laps > 1)) && lap_option=(--laps "$laps")
  # The marker first: a run stopped half-way leaves no observed.csv and is simulated again.
  mkdir -p "$dir"
  echo "$laps" > "$dir/laps"
  "$pena" simulate --scenario "$scenario" --seed "$seed" "${lap_option[@]}" --out "$dir" > /dev/null
}

# Maps and scores one mission; writes MAP.eval (and MAP.aligned.eval with --aligned).
map_one() {
  local scenario=$1 seed=$2
  local mission="$work/missions/$scenario-$seed" out="$work/maps/$scenario-$seed"
  "$pena" map --quiet --log "$mission/ff1/sensors.penalog" --out "$out" "${extra[@]}" \
    > "$out.log" 2>&1 || { echo "map-coverage: pena map failed on $scenario seed $seed ($out.log)" >&2; return 1; }
  "$pena" eval --lines "$out/lines.csv" --walls "$mission/observed.csv" > "$out.eval"
  rm -f "$out.trajectory.eval"
  if [[ -f "$out/trajectory.tum" ]]; then
    "$pena" eval --trajectory "$out/trajectory.tum" --truth "$mission/ff1/truth.tum" \
      > "$out.trajectory.eval"
  fi
  if [[ $aligned == 1 ]]; then
    python3 scripts/aligned-line-map.py "$out/trajectory.tum" "$mission/ff1/truth.tum" \
      "$out/lines.csv" "$out.aligned.csv" 2> /dev/null
    "$pena" eval --lines "$out.aligned.csv" --walls "$mission/observed.csv" > "$out.aligned.eval"
  fi
}

for m in "${missions[@]}"; do simulate $m; done
running=0
failed=0
for m in "${missions[@]}"; do
  map_one $m &
  running=$((running + 1))
  if ((running >= jobs)); then wait -n || failed=1; running=$((running - 1)); fi
done
while ((running > 0)); do wait -n || failed=1; running=$((running - 1)); done
((failed == 0)) || exit 1

# "coverage (...)   86.93 %" -> 86.93
figure() { awk -v key="$2" '$1 == key { print $(NF - 1); exit }' "$1"; }
fragmentation() { awk '$1 == "fragmentation" { print $NF; exit }' "$1"; }

# "translation RMSE [m]   0.3916" -> 0.3916 (- when the map had no trajectory of its own)
trajectory_rmse() {
  [[ -f "$1" ]] || { echo -; return; }
  awk '$1 == "translation" && $2 == "RMSE" { print $NF; exit }' "$1"
}

printf '%-12s %9s %10s %14s %16s' mission coverage precision fragmentation "trajectory RMSE"
[[ $aligned == 1 ]] && printf ' %17s' "aligned coverage"
printf '\n'
rows=()
for m in "${missions[@]}"; do
  read -r scenario seed <<< "$m"
  base="$work/maps/$scenario-$seed"
  c=$(figure "$base.eval" coverage)
  p=$(figure "$base.eval" precision)
  f=$(fragmentation "$base.eval")
  r=$(trajectory_rmse "$base.trajectory.eval")
  a=-
  [[ $aligned == 1 ]] && a=$(figure "$base.aligned.eval" coverage)
  shown=-
  [[ $r != - ]] && shown="$r m"
  printf '%-12s %8s%% %9s%% %14s %16s' "$scenario-$seed" "$c" "$p" "$f" "$shown"
  [[ $aligned == 1 ]] && printf ' %16s%%' "$a"
  printf '\n'
  rows+=("$scenario $seed $c $p $a $r")
done
printf '%s\n' "${rows[@]}" | awk -v aligned="$aligned" '
  function add(k) {
    n[k]++; c[k] += $3; p[k] += $4; a[k] += $5
    if ($6 != "-") { r[k] += $6; nr[k]++ }
  }
  { add($1); add("all"); if ($2 <= 8) add("headline") }
  function show(k, label) {
    if (!n[k]) return
    printf "mean %-40s coverage %5.1f %%, precision %5.1f %%", label " (" n[k] " maps)", c[k] / n[k], p[k] / n[k]
    if (aligned == 1) printf ", aligned coverage %5.1f %%", a[k] / n[k]
    if (nr[k]) printf ", trajectory RMSE %.3f m", r[k] / nr[k]
    printf "\n"
  }
  END {
    show("office", "office"); show("loop170", "loop170")
    show("headline", "office and loop170 seeds 1-8"); show("all", "all")
  }'
