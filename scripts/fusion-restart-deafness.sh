#!/bin/bash
# Does a pena-fusion restarted after kill -9 hear its entities again? (docs/fusion-service.md,
# "Persistence and restart".) Runs the team mission's four entities (no corrections) MISSIONS
# times; every 7 s it freezes the fusion with SIGSTOP for STOP_S seconds (a hung fusion, and the
# entities' sends pile up), kills it with SIGKILL and restarts it on the same state directory 1 s
# later. A restart is "deaf" when it marks an entity lost (4 s without a sample) that was still
# running and of which it received no sample at all before the next kill. Prints one line per
# restart and the total.
#
#   scripts/fusion-restart-deafness.sh BUILD_DIR MISSION_DIR OUT_DIR [extra pena-fusion args...]
#
# MISSION_DIR: `pena simulate --scenario team --seed 1 --out DIR`. Environment: MISSIONS (3),
# RATE (3: mission time x real time), STOP_S (2), DOMAIN (224; must be free).
set -u
build=$1 team=$2 out=$3
shift 3
extra=("$@")  # passed on to pena-fusion, e.g. --profile pena_loopback
missions=${MISSIONS:-3} rate=${RATE:-3} stop_s=${STOP_S:-2} domain=${DOMAIN:-224}
here=$(cd "$(dirname "$0")/.." && pwd)
dds="$here/deploy/dds"
export FASTRTPS_DEFAULT_PROFILES_FILE="$dds/pena-loopback.xml"
args=(--domain "$domain" --profiles-file "$dds/pena-loopback.xml"
      --profiles-file "$dds/pena-qos.xml")
fusion_bin="$build/services/fusion/pena-fusion" entity_bin="$build/services/entity/pena-entity"

start_fusion() {  # $1 run dir, $2 cycle
  "$fusion_bin" --state-dir "$1/state" --plan "$team/apriori.csv" --out "$1/fusion" \
    --no-corrections "${args[@]}" "${extra[@]}" > "$1/fusion-c$2.log" 2>&1 &
}

for m in $(seq 1 "$missions"); do
  run="$out/m$m"
  rm -rf "$run" && mkdir -p "$run"
  entities=()
  cycle=1
  start_fusion "$run" "$cycle"; fusion=$!
  for id in ff1 ff2 ff3 robot1; do
    "$entity_bin" --input "$team/$id" --rate "$rate" --out "$run/$id" --wait-for-readers 30 \
      --linger 5 "${args[@]}" > "$run/$id.log" 2>&1 &
    entities+=($!)
  done
  while true; do
    sleep 6
    running=0
    for pid in "${entities[@]}"; do kill -0 "$pid" 2> /dev/null && running=1; done
    kill -STOP "$fusion"; sleep "$stop_s"; kill -KILL "$fusion"; wait "$fusion" 2> /dev/null
    [ "$running" -eq 0 ] && break
    sleep 1
    cycle=$((cycle + 1))
    start_fusion "$run" "$cycle"; fusion=$!
  done
  wait "${entities[@]}"
done

python3 - "$out" <<'EOF'
import datetime, glob, re, sys
def stamp(line):
    return datetime.datetime.strptime(line[1:24], "%Y-%m-%d %H:%M:%S.%f")
restarts = deaf = 0
for run in sorted(glob.glob(sys.argv[1] + "/m*")):
    ended = {}  # entity -> when it wrote its outputs (exited)
    for log in glob.glob(run + "/*.log"):
        for line in open(log, errors="replace"):
            if "pena-entity" in line and ": wrote " in line:
                ended[log.rsplit("/", 1)[1][:-4]] = stamp(line)
    logs = glob.glob(run + "/fusion-c*.log")
    for log in sorted(logs, key=lambda p: int(re.findall(r"c(\d+)\.log", p)[0])):
        cycle = int(re.findall(r"c(\d+)\.log", log)[0])
        if cycle < 2:
            continue  # the first start is not a restart
        lost, heard = {}, set()
        for line in open(log, errors="replace"):
            if (found := re.search(r"\] (\S+): active -> lost", line)):
                lost[found.group(1)] = stamp(line)
            # Any sample of it: its status (finished), its data reviving it, or it back.
            if (found := re.search(r"\] (\S+)(?: is leaving|: left -> active|: lost -> active)",
                                   line)):
                heard.add(found.group(1))
        one_s = datetime.timedelta(seconds=1)
        unheard = sorted(e for e, when in lost.items()
                         if e not in heard and (e not in ended or when < ended[e] - one_s))
        restarts += 1
        deaf += bool(unheard)
        print(f"{run.rsplit('/', 1)[1]} restart {cycle - 1}: " +
              (f"deaf to {' '.join(unheard)}" if unheard else "heard every running entity"))
print(f"{deaf} deaf restarts of {restarts}")
EOF
