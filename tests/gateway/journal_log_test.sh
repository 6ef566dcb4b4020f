#!/usr/bin/env bash
# pena-gateway logs like the other daemons (services/common/logging.hpp): with stderr on the
# journal ($JOURNAL_STREAM names stderr's file, as systemd sets it) every line starts with its
# syslog priority and no time stamp; elsewhere with the time stamp; --log-level filters and
# --log-file copies; a bad --log-level is refused naming the option. No DDS (no --dds-domain);
# the UDP socket binds an ephemeral loopback port. usage: journal_log_test.sh PENA_GATEWAY
set -euo pipefail
gateway=$1
work=$(mktemp -d -t pena-gateway-log.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; for f in "$work"/*.err "$work"/*.log; do [[ -e $f ]] && { echo "== $f"; cat "$f"; }; done; exit 1; }
run() { "$gateway" --insecure-link --duration-s 0.3 --bind 127.0.0.1:0 --peer 127.0.0.1:9 "$@" > /dev/null; }

# Under the journal: "<6>[pena-gateway] [info] ...", "<4>[pena-gateway] [warning] ...".
: > "$work/journal.err"
JOURNAL_STREAM=$(stat -c '%d:%i' "$work/journal.err") run 2> "$work/journal.err" || fail "run under the journal"
grep -q '^<6>\[pena-gateway\] \[info\] gateway: udp 127.0.0.1:0 -> 127.0.0.1:9' "$work/journal.err" ||
  fail "no info line with priority 6"
grep -q '^<4>\[pena-gateway\] \[warning\] gateway: OPEN LINK' "$work/journal.err" ||
  fail "no warning line with priority 4"
grep -qv '^<[0-7]>\[pena-gateway\] ' "$work/journal.err" && fail "a line without its priority prefix"

# JOURNAL_STREAM naming another file (stderr redirected away from the journal): time stamps.
: > "$work/plain.err"
JOURNAL_STREAM=$(stat -c '%d:%i' "$work") run 2> "$work/plain.err" || fail "run with stderr not the journal"
grep -q '^\[20[0-9-]* [0-9:.]*\] \[pena-gateway\] \[warning\] gateway: OPEN LINK' "$work/plain.err" ||
  fail "no time-stamped warning line"
grep -q '^<' "$work/plain.err" && fail "a priority prefix on a stderr that is not the journal"

# --log-level warn: no info; --log-file: the same lines in the file.
run --log-level warn --log-file "$work/gateway.log" 2> "$work/warn.err" || fail "run with --log-level warn"
grep -q '\[info\]' "$work/warn.err" "$work/gateway.log" && fail "info lines at --log-level warn"
grep -q '\[pena-gateway\] \[warning\] gateway: OPEN LINK' "$work/gateway.log" || fail "--log-file has no warning"

# A bad level: refused before anything runs, naming the option.
if run --log-level loud 2> "$work/bad.err"; then fail "--log-level loud accepted"; fi
grep -q -- '--log-level' "$work/bad.err" || fail "the error does not name --log-level"
echo "pena-gateway: journal priorities, time stamps elsewhere, --log-level and --log-file: ok"
