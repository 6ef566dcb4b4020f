#!/usr/bin/env bash
# The laser odometry's figure of merit on the Freiburg logs: each log run from its logged start
# frame and from the two start frames moved by about 1 cm (X and Y), scored with
# `pena eval --relations`; prints each frame's mean translational relation error and their mean.
# `--starts 5` adds Z and W, 1 cm the other way. Single runs are chaotic (1 cm changes a log's
# figure by up to 0.4 m), so decisions take a mean over frames.
# `--starts 25`: a 5 x 5 grid of start frames, x and y -2..+2 cm around the logged start; prints
# mean, median, range and how many are below the log's target. Five frames are too few on these
# logs (docs/odometry.md, "Figures").
# One run at a time (a run takes 10-60 s; 25 intel runs about 20 min).
#
#   scripts/freiburg-starts.sh [--build DIR] [--work DIR] [--logs "intel aces mit-csail"]
#                              [--starts 3|5|25]
#                              [-- extra pena odometry options, e.g. --set local_map_keyframes=16]
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
work=/tmp/pena-freiburg-starts
logs="intel aces mit-csail"
nstarts=3
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --logs) logs=$2; shift 2 ;;
    --starts) nstarts=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "freiburg-starts: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
pena="$build/tools/pena/pena"
[[ "$nstarts" == 3 || "$nstarts" == 5 || "$nstarts" == 25 ]] ||
  { echo "freiburg-starts: --starts must be 3, 5 or 25, not '$nstarts'" >&2; exit 2; }
[[ -x "$pena" ]] || { echo "freiburg-starts: $pena not built" >&2; exit 1; }
datasets=${PENA_DATA_DIR:-data}  # the Freiburg logs (data/README.md)

# The start frames: "" is the logged first odometry pose; X and Y move it by about 1 cm, Z and W
# by about 1 cm the other way (only with --starts 5).
# The 25-frame grid: the logged start (x, y, heading in degrees) moved by -2..+2 cm in x and y.
grid() {
  local x0 y0 theta
  case "$1" in
    intel) x0=0; y0=0; theta=-0.14083 ;;
    aces) x0=0; y0=0; theta=-90 ;;
    mit-csail) x0=576.537; y0=0.107; theta=-129.21 ;;
    *) echo "freiburg-starts: no start frames for '$1'" >&2; exit 2 ;;
  esac
  awk -v x0="$x0" -v y0="$y0" -v t="$theta" 'BEGIN {
    for (i = -2; i <= 2; i++) for (j = -2; j <= 2; j++)
      printf "--start=%.3f,%.3f,%s\n", x0 + 0.01 * i, y0 + 0.01 * j, t }'
}

target() {
  case "$1" in intel) echo 0.220 ;; aces) echo 0.173 ;; mit-csail) echo 0.106 ;; esac
}

starts() {
  if [[ "$nstarts" == 25 ]]; then grid "$1"; return; fi
  case "$1" in
    intel) printf '%s\n' "" "--start=0.01,0,-0.14083" "--start=0,0.01,-0.14083" \
      "--start=-0.01,0,-0.14083" "--start=0,-0.01,-0.14083" ;;
    aces) printf '%s\n' "" "--start=0.01,-0.001,-90" "--start=-0.001,0.023,-90" \
      "--start=-0.01,0,-90" "--start=0,-0.01,-90" ;;
    mit-csail) printf '%s\n' "" "--start=576.547,0.107,-129.21" "--start=576.537,0.117,-129.21" \
      "--start=576.527,0.107,-129.21" "--start=576.537,0.097,-129.21" ;;
    *) echo "freiburg-starts: no start frames for '$1'" >&2; exit 2 ;;
  esac
}

for log in $logs; do
  errors=()
  frame=0
  while IFS= read -r start; do
    out="$work/$log-$frame"
    mkdir -p "$out"
    # shellcheck disable=SC2086
    "$pena" odometry --quiet --log "$datasets/freiburg/$log.clf.gz" --out "$out" $start \
      "${extra[@]}" >"$out/stdout"
    errors+=("$("$pena" eval --trajectory "$out/trajectory.tum" \
      --relations "$datasets/freiburg/$log.relations" |
      awk '$1 == "translation" && $2 == "[m]" { print $3 }')")
    frame=$((frame + 1))
  done < <(starts "$log" | head -n "$nstarts")
  mean=$(printf '%s\n' "${errors[@]}" | awk '{ s += $1 } END { printf "%.4f", s / NR }')
  if [[ "$nstarts" == 25 ]]; then
    printf '%s\n' "${errors[@]}" | sort -g | awk -v name="$log" -v target="$(target "$log")" '
      { v[NR] = $1; s += $1; if ($1 < target) below++ }
      END { printf "%-10s 25 frames: mean %.4f  median %.4f  min %.4f  max %.4f m; %d below %s m\n",
                   name, s / NR, v[13], v[1], v[NR], below, target }'
  elif [[ "$nstarts" == 5 ]]; then
    printf '%-10s logged %s  X %s  Y %s  Z %s  W %s  mean %s m\n' "$log" "${errors[0]}" \
      "${errors[1]}" "${errors[2]}" "${errors[3]}" "${errors[4]}" "$mean"
  else
    printf '%-10s logged %s  X %s  Y %s  mean %s m\n' "$log" "${errors[0]}" "${errors[1]}" \
      "${errors[2]}" "$mean"
  fi
done
