#!/usr/bin/env bash
# Packaging.DebInstallRunsTeamDemo: builds the Debian packages from the build tree (cpack),
# checks them with lintian (no errors), installs them with dpkg -i on this machine, runs the team
# demo from the installed binaries and configs only (the systemd units' command lines started by
# hand, as their user, with the unit's environment: no systemd here), compares its report with
# the same lockstep demo run from the build tree (deploy/demo/run-team.sh), smoke-starts
# pena-console and pena-gateway from their units, builds tests/install/consumer against the
# installed libpena-dev (find_package(pena) with no hint), and purges the packages (also on
# failure), checking that the machine is as before.
#
#   package_test.sh BUILD_DIR LIBDIR LOG   (LIBDIR: the build's CMAKE_INSTALL_LIBDIR, e.g.
#   lib/x86_64-linux-gnu; LOG: a CARMEN log the consumer runs on)
#
# Needs root (dpkg). Exits 77 (skipped) when not root or when PeNa packages, the pena user or
# /etc/pena are already on the machine: the test would change what it must leave alone.
# Runs one at a time on a machine (flock /tmp/pena-package-test.lock).
set -euo pipefail

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
BUILD=$(realpath "${1:?usage: package_test.sh BUILD_DIR LIBDIR LOG}")
LIBDIR=${2:?usage: package_test.sh BUILD_DIR LIBDIR LOG}
LOG=${3:?usage: package_test.sh BUILD_DIR LIBDIR LOG}
PACKAGES=(pena-services pena-tools libpena-dev)
UNITS=/lib/systemd/system
TEAM_RATE=5
INTERVAL=2.4

skip() { echo "SKIPPED: $*"; exit 77; }
fail() { echo "FAILED: $*" >&2; exit 1; }
# step TEXT: a timed heading.
step() { echo "== [$((SECONDS - T0)) s] $*"; }
T0=$SECONDS

[[ $(id -u) -eq 0 ]] || skip "dpkg -i needs root"
command -v lintian >/dev/null || fail "lintian is missing (scripts/setup.sh installs it)"
command -v cpack >/dev/null || fail "cpack is missing"

exec {lock_fd}>/tmp/pena-package-test.lock
flock -w 1800 "$lock_fd" || fail "another package test holds /tmp/pena-package-test.lock"

for package in "${PACKAGES[@]}"; do
  if dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null | grep -qv not-installed; then
    skip "$package is already on this machine (dpkg -l $package): the test would purge it"
  fi
done
getent passwd pena >/dev/null && skip "a user pena exists already"
[[ -e /etc/pena || -e /var/lib/pena ]] && skip "/etc/pena or /var/lib/pena exists already"

WORK=$(mktemp -d -t pena-package-test.XXXXXX)
chmod 0755 "$WORK"  # the services' user reads the mission from here
PIDS=()
INSTALLED=0
TEAM=()

stop_processes() {
  local pid
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for _ in $(seq 50); do
    local alive=0
    for pid in "${PIDS[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${PIDS[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
  PIDS=()
}

# On every exit: stop what runs, remove what the test added to /etc/pena, purge the packages,
# and check that nothing of them is left.
cleanup() {
  local status=$?
  stop_processes
  if ((INSTALLED)); then
    for id in "${TEAM[@]}"; do rm -f "/etc/pena/entity/$id.conf"; done
    dpkg --purge "${PACKAGES[@]}" > "$WORK/purge.log" 2>&1 || { cat "$WORK/purge.log"; status=1; }
    local left=()
    for path in /etc/pena /var/lib/pena /usr/share/pena /usr/include/pena /usr/bin/pena "/usr/$LIBDIR/cmake/pena" \
                /usr/bin/pena-entity "$UNITS/pena-fusion.service" "$UNITS/pena-entity@.service"; do
      [[ -e $path ]] && left+=("$path")
    done
    getent passwd pena >/dev/null && left+=("user pena")
    getent group pena >/dev/null && left+=("group pena")
    if ((${#left[@]})); then
      echo "FAILED: left after dpkg --purge: ${left[*]}" >&2
      status=1
    fi
  fi
  rm -rf "$WORK"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# ---------------------------------------------------------------------------------------------
step "cpack -G DEB (build tree $BUILD)"
cpack_start=$SECONDS
(cd "$BUILD" && cpack -G DEB -B "$WORK/deb") > "$WORK/cpack.log" 2>&1 ||
  { cat "$WORK/cpack.log"; fail "cpack"; }
DEBS=()
for package in "${PACKAGES[@]}"; do
  deb=$(ls "$WORK"/deb/"$package"_*.deb 2>/dev/null | head -n1)
  [[ -n $deb ]] || { cat "$WORK/cpack.log"; fail "cpack made no $package package"; }
  DEBS+=("$deb")
done
echo "cpack: $((SECONDS - cpack_start)) s"
for deb in "${DEBS[@]}"; do
  printf '%-40s %8d kB (installed %s kB)\n' "$(basename "$deb")" "$(($(stat -c %s "$deb") / 1024))" \
    "$(dpkg-deb -f "$deb" Installed-Size)"
done

# Control fields: the binary packages depend on Debian's libraries (dpkg-shlibdeps), the
# services package on adduser, and /etc/pena is conffiles.
dpkg-deb -f "${DEBS[0]}" Depends | grep -q libfastrtps || fail "pena-services: no Fast DDS dependency"
dpkg-deb -f "${DEBS[0]}" Depends | grep -q adduser || fail "pena-services: no adduser dependency"
dpkg-deb -f "${DEBS[1]}" Depends | grep -q libc6 || fail "pena-tools: no shared-library dependencies"
dpkg-deb -f "${DEBS[2]}" Depends | grep -q libeigen3-dev || fail "libpena-dev: no libeigen3-dev dependency"
dpkg-deb -I "${DEBS[0]}" conffiles | grep -qx /etc/pena/fusion.conf || fail "pena-services: no conffiles"
# libpena-dev: the libraries and the CMake package in the build's library directory (multiarch
# on Debian: /usr/lib/x86_64-linux-gnu), nothing directly in /usr/lib unless that is it.
dpkg-deb -c "${DEBS[2]}" | awk '{print $NF}' > "$WORK/libpena-dev.files"
for file in "./usr/$LIBDIR/libpena_odometry.a" "./usr/$LIBDIR/cmake/pena/penaConfig.cmake"; do
  grep -qx "$file" "$WORK/libpena-dev.files" || fail "libpena-dev has no $file"
done
if [[ $LIBDIR != lib ]] && grep -q '^\./usr/lib/[^/]*\.a$' "$WORK/libpena-dev.files"; then
  fail "libpena-dev puts libraries directly in /usr/lib, not /usr/$LIBDIR"
fi
echo "libpena-dev: libraries and cmake/pena in /usr/$LIBDIR"
for package in "${!DEBS[@]}"; do
  echo "${PACKAGES[$package]}: Depends: $(dpkg-deb -f "${DEBS[$package]}" Depends)"
done

step "lintian"
lintian_start=$SECONDS
lintian --no-tag-display-limit "${DEBS[@]}" > "$WORK/lintian.log" 2>&1 || true
echo "lintian: $((SECONDS - lintian_start)) s"
grep -E '^[EWI]: ' "$WORK/lintian.log" | sort | uniq -c || true
if grep -q '^E: ' "$WORK/lintian.log"; then fail "lintian reports errors"; fi

step "dpkg -i"
INSTALLED=1
dpkg -i "${DEBS[@]}" > "$WORK/install.log" 2>&1 || { cat "$WORK/install.log"; fail "dpkg -i"; }
getent passwd pena >/dev/null || fail "postinst made no user pena"
# The installed loopback profile is the repository's: every participant stays on loopback.
cmp /etc/pena/dds/pena-loopback.xml "$REPO/deploy/dds/pena-loopback.xml" ||
  fail "/etc/pena/dds/pena-loopback.xml differs from deploy/dds/pena-loopback.xml"
if command -v systemd-analyze >/dev/null; then
  # Unit syntax; the instance needs its config, the gateway its key: verify the others only.
  systemd-analyze verify "$UNITS/pena-fusion.service" "$UNITS/pena-console.service" \
    > "$WORK/verify.log" 2>&1 || { cat "$WORK/verify.log"; fail "systemd-analyze verify"; }
fi

# ---------------------------------------------------------------------------------------------
# What systemd would run for UNIT (instance INSTANCE): the ExecStart words with %i, %S, ${VAR}
# (one word) and $VAR (split at blanks) expanded from Environment=, EnvironmentFile=,
# StateDirectory= and LoadCredential= (the credentials directory CREDS). Sets the arrays
# UNIT_ARGV and UNIT_ENV ("KEY=VALUE") and UNIT_STATE (the state directory, if any). Values in
# OVERRIDES ("KEY=VALUE" ...) replace the environment file's, as an administrator's edit would.
unit_command() {
  local unit=$1 instance=$2 creds=$3
  shift 3
  local -A env=()
  local line key value word
  UNIT_STATE=""
  while IFS= read -r line; do
    line=${line//%i/$instance}
    line=${line//%S//var/lib}
    case $line in
      Environment=*) value=${line#Environment=}; env[${value%%=*}]=${value#*=} ;;
      EnvironmentFile=*)
        while IFS= read -r value; do
          [[ $value =~ ^([A-Za-z_][A-Za-z0-9_]*)=\"?([^\"]*)\"?$ ]] || continue
          env[${BASH_REMATCH[1]}]=${BASH_REMATCH[2]}
        done < "${line#EnvironmentFile=}" ;;
      StateDirectory=*) UNIT_STATE=/var/lib/${line#StateDirectory=}; env[STATE_DIRECTORY]=$UNIT_STATE ;;
      LoadCredential=*) env[CREDENTIALS_DIRECTORY]=$creds ;;
      User=*) [[ ${line#User=} == pena ]] || fail "$unit runs as ${line#User=}, not pena" ;;
    esac
  done < "$UNITS/$unit"
  for value in "$@"; do env[${value%%=*}]=${value#*=}; done
  line=$(sed -n 's/^ExecStart=//p' "$UNITS/$unit")
  line=${line//%i/$instance}
  UNIT_ARGV=()
  read -ra words <<< "$line"
  for word in "${words[@]}"; do
    if [[ $word =~ ^\$([A-Za-z_][A-Za-z0-9_]*)$ ]]; then
      read -ra value <<< "${env[${BASH_REMATCH[1]}]:-}"
      UNIT_ARGV+=("${value[@]}")
    else
      while [[ $word =~ \$\{([A-Za-z_][A-Za-z0-9_]*)\} ]]; do
        word=${word/"${BASH_REMATCH[0]}"/"${env[${BASH_REMATCH[1]}]:-}"}
      done
      UNIT_ARGV+=("$word")
    fi
  done
  UNIT_ENV=("PATH=/usr/bin:/bin")
  for key in "${!env[@]}"; do UNIT_ENV+=("$key=${env[$key]}"); done
}

# run_unit LOG ARGS...: starts the last unit_command as user pena in its state directory (made
# as StateDirectory= would), with exactly the unit's environment and ARGS appended, no new
# privileges and no capabilities (NoNewPrivileges=, CapabilityBoundingSet=); sets PID, the
# service's own (setpriv and env exec it).
run_unit() {
  local log=$1
  shift
  if [[ -n $UNIT_STATE ]]; then install -d -o pena -g pena "$UNIT_STATE"; fi
  (cd "${UNIT_STATE:-/}" &&
   exec setpriv --reuid=pena --regid=pena --init-groups --no-new-privs --inh-caps=-all \
     --bounding-set=-all env -i "${UNIT_ENV[@]}" "${UNIT_ARGV[@]}" "$@") > "$log" 2>&1 &
  PID=$!
  PIDS+=("$PID")
}

# shellcheck source=../../deploy/dds/domain-lock.sh
source "$REPO/deploy/dds/domain-lock.sh"
pena_lock_dds_domain DOMAIN

# ---------------------------------------------------------------------------------------------
step "pena simulate (installed /usr/bin/pena), team mission seed 1"
MISSION=$WORK/mission
/usr/bin/pena simulate --scenario team --seed 1 --out "$MISSION" > "$WORK/simulate.log"
chmod -R a+rX "$MISSION"
for dir in "$MISSION"/*/; do [[ -f $dir/sensors.penalog ]] && TEAM+=("$(basename "$dir")"); done
((${#TEAM[@]} > 0)) || fail "the simulated mission has no entity"
TEAM_CSV=$(IFS=,; echo "${TEAM[*]}")

step "team demo from the installed units (DDS domain $DOMAIN, ${TEAM[*]})"
demo_start=$SECONDS
mkdir -p "$WORK/installed/logs"
# pena-fusion: its unit's command line (/etc/pena/fusion.conf) plus the demo's plan, domain and
# lockstep (deploy/demo/run-team.sh gives the same).
unit_command pena-fusion.service "" ""
run_unit "$WORK/installed/logs/fusion.log" --plan "$MISSION/apriori.csv" --domain "$DOMAIN" \
  --correction-interval "$INTERVAL" --lockstep --lockstep-entities "$TEAM_CSV"
FUSION_PID=$PID
# One pena-entity@<id> per member: /etc/pena/entity/<id>.conf is the shipped example, as an
# administrator copies it; the recorded input, rate, domain and lockstep come on the command line.
ENTITY_PIDS=()
for id in "${TEAM[@]}"; do
  cp /etc/pena/entity/example.conf "/etc/pena/entity/$id.conf"
  unit_command pena-entity@.service "$id" ""
  run_unit "$WORK/installed/logs/$id.log" --input "$MISSION/$id" --rate "$TEAM_RATE" \
    --domain "$DOMAIN" --wait-for-readers 20 --linger 5 --await-corrections "$INTERVAL"
  ENTITY_PIDS+=("$PID")
done
for i in "${!ENTITY_PIDS[@]}"; do
  wait "${ENTITY_PIDS[$i]}" ||
    { cat "$WORK/installed/logs/${TEAM[$i]}.log"; fail "pena-entity@${TEAM[$i]} failed"; }
done
sleep 2
kill -TERM "$FUSION_PID"
wait "$FUSION_PID" || { cat "$WORK/installed/logs/fusion.log"; fail "pena-fusion failed"; }
PIDS=()
echo "installed team run: $((SECONDS - demo_start)) s"
# pena report reads RUN/fusion and RUN/<id>: the units' state directories.
RUN=$WORK/installed/run
mkdir -p "$RUN"
ln -s /var/lib/pena/fusion "$RUN/fusion"
for id in "${TEAM[@]}"; do ln -s "/var/lib/pena/entity/$id" "$RUN/$id"; done
/usr/bin/pena report --mission "$MISSION" --run "$RUN" --out "$WORK/installed/report" \
  > "$WORK/installed/report.log" || { cat "$WORK/installed/report.log"; fail "pena report"; }

step "the same demo from the build tree (deploy/demo/run-team.sh)"
ref_start=$SECONDS
PENA_BUILD=$BUILD PENA_DEMO_CONSOLE=0 PENA_DDS_DOMAIN=$DOMAIN PENA_DEMO_MISSION=$MISSION \
  PENA_DEMO_RATE=$TEAM_RATE PENA_DEMO_CORRECTION_INTERVAL=$INTERVAL \
  bash "$REPO/deploy/demo/run-team.sh" "$WORK/build-tree" > "$WORK/build-tree.log" 2>&1 ||
  { tail -n 30 "$WORK/build-tree.log"; fail "run-team.sh from the build tree"; }
echo "build-tree team run: $((SECONDS - ref_start)) s"

# The figures docs/demo.md quotes: accuracy per entity (with and without corrections, poses) and
# the map scores. (Bytes count wall-clock heartbeats and latency is wall time: both differ.)
figures() {
  sed -n "/^## Accuracy per entity/,/^## Bytes per topic/p" "$1" | grep -v "^## Bytes"
}
figures "$WORK/installed/report/report.md"
figures "$WORK/installed/report/report.md" | grep -q "^| ${TEAM[0]} |" ||
  fail "no accuracy figures in the installed run's report.md"
if ! diff <(figures "$WORK/build-tree/report.md") <(figures "$WORK/installed/report/report.md") \
     > "$WORK/report.diff"; then
  cat "$WORK/report.diff"
  fail "the installed demo's report differs from the build tree's"
fi
echo "the figures agree with the build tree's run"

# ---------------------------------------------------------------------------------------------
step "pena-console and pena-gateway from their units"
unit_command pena-console.service "" "" \
  "PENA_CONSOLE_ARGS=--bind 127.0.0.1 --port 0 --domain $DOMAIN --port-file $WORK/console.port"
touch "$WORK/console.port" && chown pena "$WORK/console.port" && : > "$WORK/console.port"
run_unit "$WORK/console.log"
CONSOLE_PID=$PID
for _ in $(seq 100); do [[ -s $WORK/console.port ]] && break; sleep 0.1; done
[[ -s $WORK/console.port ]] || { cat "$WORK/console.log"; fail "pena-console did not start"; }
exec {http}<>"/dev/tcp/127.0.0.1/$(cat "$WORK/console.port")"
printf 'GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n' >&"$http"
head -n1 <&"$http" | grep -q ' 200 ' || fail "pena-console does not serve its page"
exec {http}>&-
kill -TERM "$CONSOLE_PID"
wait "$CONSOLE_PID" || { cat "$WORK/console.log"; fail "pena-console did not stop cleanly"; }
echo "pena-console: served its page on 127.0.0.1, stopped cleanly"

# The link key, as systemd's LoadCredential= hands it over: a copy readable by the user only.
/usr/bin/pena-gateway --generate-link-key "$WORK/link.key" > /dev/null
install -d -o pena -m 0700 "$WORK/credentials"
install -o pena -m 0400 "$WORK/link.key" "$WORK/credentials/link.key"
unit_command pena-gateway.service "" "$WORK/credentials" \
  "PENA_GATEWAY_ARGS=--name building --role building --dds-domain $DOMAIN --bind 127.0.0.1:0 --peer 127.0.0.1:9"
PIDS=()
run_unit "$WORK/gateway.log"
GATEWAY_PID=$PID
sleep 3
kill -0 "$GATEWAY_PID" 2>/dev/null || { cat "$WORK/gateway.log"; fail "pena-gateway exited"; }
kill -TERM "$GATEWAY_PID"
wait "$GATEWAY_PID" || { cat "$WORK/gateway.log"; fail "pena-gateway did not stop cleanly"; }
grep -q '"name"' "$WORK/gateway.log" || { cat "$WORK/gateway.log"; fail "pena-gateway wrote no summary"; }
echo "pena-gateway: ran with the credential link key, stopped cleanly"
PIDS=()

step "find_package(pena) from the installed libpena-dev (tests/install/consumer)"
cmake -S "$REPO/tests/install/consumer" -B "$WORK/consumer" -DCMAKE_BUILD_TYPE=Release \
  > "$WORK/consumer.log" 2>&1 || { cat "$WORK/consumer.log"; fail "configure the consumer"; }
grep -qx "pena_DIR:PATH=/usr/$LIBDIR/cmake/pena" "$WORK/consumer/CMakeCache.txt" ||
  fail "the consumer found pena elsewhere: $(grep '^pena_DIR' "$WORK/consumer/CMakeCache.txt")"
cmake --build "$WORK/consumer" > "$WORK/consumer.log" 2>&1 ||
  { cat "$WORK/consumer.log"; fail "build the consumer"; }
"$WORK/consumer/odometry_on_log" "$LOG" 200 || fail "the consumer on $LOG"

step "passed; purging"
