#!/usr/bin/env bash
# End to end through network namespaces: two pena-gateway processes across a tc-shaped
# 9.6 kbit/s link with a silent 8 s outage (deploy/link/run-link.sh), sealed with a key made for
# the run. Passes if the far side's maps equal the near side's, poses and alarms arrived, no
# delta is pending, and no datagram was rejected.
# Skips (exit 77) without root, ip, tc or python3. usage: netns_link_test.sh PENA_GATEWAY
set -euo pipefail
gateway="$1"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [[ $(id -u) -ne 0 ]] || ! command -v ip >/dev/null || ! command -v tc >/dev/null ||
   ! command -v python3 >/dev/null; then
  echo "skipped: needs root, ip, tc and python3"; exit 77
fi
out="$(mktemp -d -t pena-netns-test.XXXXXX)"
trap 'rm -rf "$out"' EXIT
result="$("$here/../../deploy/link/run-link.sh" --gateway "$gateway" --rate-kbit 9.6 --duration-s 24 \
  --outage 6:14 --map-until-s 12 --out "$out/run")" || { echo "run-link.sh failed: $result"; cat "$out"/run/*.out; exit 1; }
echo "$result"
python3 - "$result" <<'PY'
import json, sys
r = json.loads(sys.argv[1])
problems = [what for what, bad in [
    ("maps differ", not r["maps_equal"]), ("no poses", r["poses_received"] == 0),
    ("not sealed", not r["sealed"]), ("datagrams rejected", r["frames_rejected"] != 0),
    ("no alarms", r["alarms_received"] == 0), ("deltas pending", r["pending_deltas"] != 0),
    ("no outage seen", r["max_pose_gap_s"] < 8.0), ("stale poses", r["pose_age_p99_s"] > 2.0)] if bad]
print("FAILED: " + ", ".join(problems) if problems else "passed")
sys.exit(1 if problems else 0)
PY
