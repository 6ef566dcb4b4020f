#!/usr/bin/env bash
# The people's laser odometry over many simulated missions, for deciding a people default
# (docs/odometry.md): per entity the translation RMSE, the final error in % of the path
# and the heading RMSE against truth.tum, then the means and how many runs end over 1 %.
#
#   scripts/people-odometry-sweep.sh [--build DIR] [--work DIR] [--tag NAME]
#                                    [--entities "M/ffN ..."] [-- extra pena odometry options]
#
# Default entities: ff1 of /work/missions/office1-5 and loop1701-5, ff1-ff3 of team1-3 (set
# PENA_MISSIONS to read them elsewhere). Extra seeds: `pena simulate --scenario office --seed 6
# --out DIR/office6`, then pass "DIR/office6/ff1" in --entities. One job at a time (2-20 s each).
# Prints "mission/entity rmse_m final_% heading_deg" rows, then "mean ..." and "over1% N of M";
# runs are kept in WORK/TAG/<mission>-<entity>. Example, an option set A:
#   scripts/people-odometry-sweep.sh --tag A -- --set dead_reckoning.stride_interpolation.enabled=0 \
#       --set dead_reckoning.max_stride_period_s=1.5
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
work=/tmp/pena-people-sweep
tag=run
missions=${PENA_MISSIONS:-/work/missions}
entities=""
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --tag) tag=$2; shift 2 ;;
    --entities) entities=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "people-odometry-sweep: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
pena="$build/tools/pena/pena"
[[ -x "$pena" ]] || { echo "people-odometry-sweep: $pena not built" >&2; exit 1; }
if [[ -z "$entities" ]]; then
  for m in office1 office2 office3 office4 office5 loop1701 loop1702 loop1703 loop1704 loop1705; do
    entities+=" $missions/$m/ff1"
  done
  for m in team1 team2 team3; do
    for f in ff1 ff2 ff3; do entities+=" $missions/$m/$f"; done
  done
fi
mkdir -p "$work/$tag"

# number NAME JSON: the value of "NAME": in pena eval's one-line JSON.
number() { sed -n "s/.*\"$1\": *\([-0-9.e]*\).*/\1/p" <<<"$2"; }

rows=()
for entity in $entities; do
  name="$(basename "$(dirname "$entity")")/$(basename "$entity")"
  out="$work/$tag/${name/\//-}"
  "$pena" odometry --quiet --log "$entity/sensors.penalog" --out "$out" "${extra[@]}" >/dev/null
  json=$("$pena" eval --trajectory "$out/trajectory.tum" --truth "$entity/truth.tum" --json)
  row=$(printf '%-16s %7.3f %7.3f %7.3f' "$name" "$(number translation_rmse_m "$json")" \
        "$(number final_error_percent_of_path "$json")" "$(number heading_rmse_deg "$json")")
  echo "$row"
  rows+=("$row")
done
printf '%s\n' "${rows[@]}" | awk '{n++; r+=$2; f+=$3; h+=$4; if ($3 > 1.0) over++}
  END {printf "mean             %7.3f %7.3f %7.3f\nover1%% %d of %d\n", r/n, f/n, h/n, over, n}'
