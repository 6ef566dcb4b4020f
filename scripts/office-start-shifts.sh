#!/usr/bin/env bash
# The office localisation figure over small start shifts: `pena localise` with the true start pose and
# the same moved along x by a few millimetres, per simulated office mission; prints each run's
# in-map RMS position and heading error (summary.json's truth block) and each mission's mean.
# Single runs are chaotic (1 mm moves a seed's figure by up to 0.08 m), so compare variants on the
# means.
# One run at a time (5-10 s each).
#
#   scripts/office-start-shifts.sh [--build DIR] [--work DIR] [--missions "DIR ..."]
#                                  [--shifts "0 0.001 0.002 0.005 0.01"]
#                                  [-- extra pena localise options, e.g. --set min_score=0.5]
# Default missions: /work/missions/office1-5 (PENA_MISSIONS to read them elsewhere), each made
# with `pena simulate --scenario office --seed N --out DIR/officeN`.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
work=/tmp/pena-office-shifts
missions_dir=${PENA_MISSIONS:-/work/missions}
missions=""
shifts="0 0.001 0.002 0.005 0.01"
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --missions) missions=$2; shift 2 ;;
    --shifts) shifts=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "office-start-shifts: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
pena="$build/tools/pena/pena"
[[ -x "$pena" ]] || { echo "office-start-shifts: $pena not built" >&2; exit 1; }
[[ -n "$missions" ]] || for s in 1 2 3 4 5; do missions+=" $missions_dir/office$s"; done
mkdir -p "$work"

for mission in $missions; do
  name=$(basename "$mission")
  # The first truth pose: "stamp x y z qx qy qz qw", a yaw-only quaternion.
  read -r _ x y _ _ _ qz qw < <(grep -v '^#' "$mission/ff1/truth.tum" | head -n 1)
  theta_deg=$(awk -v z="$qz" -v w="$qw" 'BEGIN {printf "%.9f", 2 * atan2(z, w) * 45 / atan2(1, 1)}')
  for d in $shifts; do
    start_x=$(awk -v x="$x" -v d="$d" 'BEGIN {printf "%.9f", x + d}')
    out="$work/$name-$d"
    "$pena" localise --quiet --log "$mission/ff1/sensors.penalog" --map "$mission/apriori.csv" \
      --start "$start_x,$y,$theta_deg" --out "$out" "${extra[@]}" >/dev/null
    rms=$(sed -n 's/.*"in_map_rms_m": *\([-0-9.e]*\).*/\1/p' "$out/summary.json" | head -n 1)
    heading=$(sed -n 's/.*"in_map_heading_rms_deg": *\([-0-9.e]*\).*/\1/p' "$out/summary.json" | head -n 1)
    printf '%-10s %-6s %7.3f %7.2f\n' "$name" "$d" "$rms" "$heading"
  done
done | awk '{print; n[$1]++; r[$1]+=$3; all+=$3; count++}
  END {for (m in n) printf "mean %-10s %7.3f\n", m, r[m] / n[m]; printf "mean all        %7.3f over %d runs\n", all / count, count}'
