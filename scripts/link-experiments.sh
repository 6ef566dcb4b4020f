#!/usr/bin/env bash
# The link experiments (docs/link-experiments.md), one command, as root:
#   sudo scripts/link-experiments.sh [--quick] [--out DIR] [--build DIR] [--jobs N] [--no-docs]
#        [--modes "gateway dds"] [--skip-existing] [--secure]
# Full: the `team` mission replayed in real time through a radio link shaped to 9.6, 28.8, 64
# and 256 kbit/s with a 30 s outage, once through the pena-gateway pair and once as plain Fast
# DDS with flow controllers, plus a gateway run at 9.6 kbit/s with emulated delay and loss;
# then line maps against grids, and the report (docs/link-experiments.md between its GENERATED
# markers, plots docs/images/link-*.png). --quick: only 9.6 kbit/s, both modes, a shortened team
# mission (first 10 waypoints each) in real time, outage 15-45 s (~2.5 min; the CI test), report
# under OUT only. --secure: every run's participants with DDS Security (docs/security.md).
# Each run lives in its own network namespaces (deploy/link/team-link-run.sh); nothing leaves
# the machine; everything is removed on any exit.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=0; out=""; build="${PENA_BUILD:-$repo/build}"; jobs=2; docs=1; modes="gateway dds"
skip_existing=0; secure_opt=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1; shift;;
    --out) out="$2"; shift 2;;
    --build) build="$2"; shift 2;;
    --jobs) jobs="$2"; shift 2;;
    --modes) modes="$2"; shift 2;;
    --no-docs) docs=0; shift;;
    --skip-existing) skip_existing=1; shift;;
    --secure) secure_opt=--secure; shift;;
    -h|--help) sed -n 2,14p "$0"; exit 0;;
    *) echo "link-experiments.sh: unknown option '$1'" >&2; exit 2;;
  esac
done
[[ $(id -u) == 0 ]] || { echo "link-experiments.sh: needs root (network namespaces)" >&2; exit 77; }
out=${out:-/tmp/pena-link-experiments$([[ $quick == 1 ]] && echo -quick)}
mkdir -p "$out"; out=$(cd "$out" && pwd)
build=$(cd "$build" && pwd)
# Run a copy of the harness: bash reads scripts as it goes, so editing deploy/link/ during a
# long matrix must not change the runs in flight.
mkdir -p "$out/harness"; cp "$repo"/deploy/link/*.sh "$repo"/deploy/link/*.py "$out/harness/"
run=$out/harness/team-link-run.sh; export PENA_REPO=$repo
for bin in tools/pena/pena services/monitor/pena-monitor services/monitor/pena-link-plot \
           services/monitor/pena-link-gridcost; do
  [[ -x $build/$bin ]] || { echo "link-experiments.sh: $build/$bin not built" >&2; exit 2; }
done

pids=()
cleanup() { local pid; for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT
trap 'exit 130' INT TERM

# The mission: `team`; --quick keeps each firefighter's first 10 waypoints and the robot's first
# 4 (60-80 s of mission),
# so the run takes about 2 minutes in real time.
if [[ ! -d $out/mission ]]; then
  scenario=team
  if ((quick)); then
    scenario=$out/team-short.scenario
    "$build/tools/pena/pena" simulate --scenario team --print-scenario | awk '
      $1 == "name" { print "name team-short"; next }
      $1 == "waypoint" { if (++count[$2] > ($2 ~ /^robot/ ? 4 : 10)) next }
      { print }' > "$scenario"
  fi
  "$build/tools/pena/pena" simulate --scenario "$scenario" --seed 1 --out "$out/mission" > "$out/simulate.log"
fi

# The matrix: NAME|MODE|RATE_KBIT|team-link-run options. Variants: gateway (pena-gateway's
# defaults: 480-byte packets; map updates larger than the room in a packet go in pieces),
# gateway-p1400 (--packet-bytes 1400 --burst-bits 16000: fewer, larger packets; see
# docs/link-experiments.md), gateway-open (the gateway pair with open frames, --insecure-link, to
# measure what the seal costs; docs/security.md), dds (plain DDS with flow controllers). Every
# gateway variant but gateway-open is sealed with a key made for the run.
variant_opts() {
  case "$1" in
    gateway-p1400) echo "--mode gateway -- --packet-bytes 1400 --burst-bits 16000";;
    gateway) echo "--mode gateway";;
    gateway-open) echo "--mode gateway --insecure-link";;
    dds) echo "--mode dds";;
  esac
}
specs=()
if ((quick)); then
  for mode in $modes; do
    specs+=("$mode-9.6|$mode|9.6|--entity-rate 1 --outage 15:45 --settle-s 60")
  done
else
  for rate in 9.6 28.8 64 256; do
    for mode in $modes; do specs+=("$mode-$rate|$mode|$rate|--entity-rate 1 --outage 60:90 --settle-s 90"); done
  done
  for mode in $modes; do
    [[ $mode == gateway* ]] && specs+=("$mode-9.6-lossy|$mode|9.6|--entity-rate 1 --outage 60:90 --settle-s 90 --delay-s 0.3 --loss 0.05")
  done
fi

status=0
active=0
for spec in "${specs[@]}"; do
  IFS='|' read -r name mode rate extra <<< "$spec"
  if ((skip_existing)) && [[ -f $out/runs/$name/result.json ]]; then echo "== $name: kept"; continue; fi
  while (( $(jobs -rp | wc -l) >= jobs )); do sleep 2; done
  echo "== $name ($(date -u +%H:%M:%S))"
  # shellcheck disable=SC2086
  nice "$run" --build "$build" --mission "$out/mission" --out "$out/runs/$name" \
    --rate-kbit "$rate" $secure_opt $extra $(variant_opts "$mode") > "$out/$name.log" 2>&1 &
  pids+=($!)
  sleep 5
done
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
((status == 0)) || echo "link-experiments.sh: a run failed; see $out/*.log" >&2

images=$out/images; mkdir -p "$images"
python3 "$out/harness/report.py" --out "$out" --build "$build" --images "$images" \
  --command "scripts/link-experiments.sh$([[ $quick == 1 ]] && echo ' --quick')" > "$out/report.md"
if ((docs && !quick)); then
  python3 "$out/harness/report.py" --splice "$repo/docs/link-experiments.md" < "$out/report.md"
  cp "$images"/link-*.png "$repo/docs/images/"
  echo "== wrote docs/link-experiments.md and docs/images/link-*.png"
fi
echo "== report: $out/report.md"
exit $status
